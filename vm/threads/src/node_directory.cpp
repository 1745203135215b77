#include "meldvm/node_directory.hpp"

#include <string>

#include "meldvm/arith.hpp"

namespace meldvm::threads {

NodeDirectory::NodeDirectory(NodeId graphNodes, ThreadId threads, bool threadNodes)
    : graph_(graphNodes),
      threads_(threads),
      createdBase_(graphNodes + (threadNodes ? threads : 0)),
      owner_(new std::atomic<std::uint16_t>[graphNodes]),
      blockOwner_(new std::atomic<ThreadId>[kMaxBlocks]) {
  for (ThreadId t = 0; t < threads; ++t)
    for (NodeId n = firstOwned(t); n < endOwned(t); ++n)
      owner_[n].store(std::uint16_t(t), std::memory_order_relaxed);
  for (std::uint32_t b = 0; b < kMaxBlocks; ++b) blockOwner_[b].store(kNoThread, std::memory_order_relaxed);
}

NodeId NodeDirectory::allocateBlock(ThreadId t, NodeId& count) {
  const std::uint32_t block = blocks_.fetch_add(1, std::memory_order_relaxed);
  const std::uint64_t first = std::uint64_t(createdBase_) + std::uint64_t(block) * kBlockIds;
  if (block >= kMaxBlocks || first + kBlockIds > 0xFFFFFFF0ull)
    throw RuntimeError("exists: no node ids left (" + std::to_string(kMaxBlocks) + " blocks of " +
                       std::to_string(kBlockIds) + " created nodes)");
  blockOwner_[block].store(t, std::memory_order_release);
  count = kBlockIds;
  return NodeId(first);
}

NodeId NodeDirectory::idEnd() const {
  const std::uint64_t blocks = std::min<std::uint32_t>(blocks_.load(std::memory_order_acquire), kMaxBlocks);
  return NodeId(createdBase_ + blocks * kBlockIds);
}

}  // namespace meldvm::threads
