// Which thread owns which node in a threaded run. The graph's nodes are cut into contiguous
// ranges, one per thread (the established VM's static partition); thread t's thread node is
// N + t; a thread creates nodes (exists) from blocks of 16384 ids it takes in turn (§6.10).
// Read by every thread on every fact for another thread's node: no lock, the initial ranges are
// arithmetic and a block's owner is written before any of its ids can appear in a fact.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "meldvm/shard.hpp"

namespace meldvm::threads {

class NodeDirectory {
 public:
  static constexpr NodeId kBlockIds = 16384;
  static constexpr std::uint32_t kMaxBlocks = 1u << 16;

  NodeDirectory(NodeId graphNodes, ThreadId threads, bool threadNodes);

  ThreadId threads() const { return threads_; }
  NodeId graphNodes() const { return graph_; }
  NodeId firstOwned(ThreadId t) const { return NodeId(std::uint64_t(graph_) * t / threads_); }
  NodeId endOwned(ThreadId t) const { return firstOwned(t + 1); }

  ThreadId ownerOf(NodeId n) const {
    if (n < graph_) return ThreadId((std::uint64_t(n + 1) * threads_ + graph_ - 1) / graph_ - 1);
    if (n < createdBase_) return n - graph_;  // a thread node
    const std::uint64_t block = (n - createdBase_) / kBlockIds;
    return block < kMaxBlocks ? blockOwner_[block].load(std::memory_order_acquire) : kNoThread;
  }
  // A block of ids for nodes thread t creates; throws RuntimeError when ids run out.
  NodeId allocateBlock(ThreadId t, NodeId& count);
  // One past the highest id handed out so far (the dump walks the ids below it).
  NodeId idEnd() const;

 private:
  NodeId graph_;
  ThreadId threads_;
  NodeId createdBase_;  // the first id of the first block of created nodes
  std::unique_ptr<std::atomic<ThreadId>[]> blockOwner_;
  std::atomic<std::uint32_t> blocks_{0};
};

}  // namespace meldvm::threads
