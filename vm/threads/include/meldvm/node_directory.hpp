// Which thread (or simulated core) owns which node in a threaded run. The graph's nodes start cut into
// contiguous ranges, one per thread, of about equal weight (a node weighs one plus the facts of its
// axioms), and move when threads steal them; thread t's thread node is N + t; a thread creates nodes (exists)
// from blocks of 16384 ids it takes in turn (§6.10). Read by every thread on every fact it sends: no lock. A
// graph node's owner changes only while every thread waits in the rebalancing barrier (worker.cpp), and a
// block's owner is written before any of its ids can appear in a fact. The graph nodes' owners are
// packed (one bit each at two threads): every fact sent asks for its destination's owner, and a
// 2-byte entry per node missed the cache on large graphs (8 % of shortest-path's time at -j 2).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "meldvm/shard.hpp"

namespace meldvm::threads {

class NodeDirectory {
 public:
  static constexpr NodeId kBlockIds = 16384;
  static constexpr std::uint32_t kMaxBlocks = 1u << 16;

  // The initial ranges weigh the nodes by their axioms (program.nodeAxioms); nodes beyond the
  // program's (a graph the run was told is larger) weigh one.
  NodeDirectory(const Program& program, NodeId graphNodes, ThreadId threads, bool threadNodes);

  ThreadId threads() const { return threads_; }
  NodeId graphNodes() const { return graph_; }
  NodeId firstOwned(ThreadId t) const { return cuts_[t]; }
  NodeId endOwned(ThreadId t) const { return cuts_[t + 1]; }

  ThreadId ownerOf(NodeId n) const {
    if (n < graph_) return graphOwner(n);
    if (n < createdBase_) return n - graph_;  // a thread node
    const std::uint64_t block = (n - createdBase_) / kBlockIds;
    return block < kMaxBlocks ? blockOwner_[block].load(std::memory_order_acquire) : kNoThread;
  }
  // Graph node n now belongs to thread t (only inside the rebalancing barrier, and only by n's
  // owner: other threads may move other nodes of the same word at the same time, hence the one
  // atomic exclusive-or that changes n's bits alone).
  void moveNode(NodeId n, ThreadId t) {
    const std::uint64_t change = std::uint64_t(graphOwner(n) ^ t) << ownerShift(n);
    owners_[n >> nodesPerWordLog_].fetch_xor(change, std::memory_order_relaxed);
  }
  // A block of ids for nodes thread t creates; throws RuntimeError when ids run out.
  NodeId allocateBlock(ThreadId t, NodeId& count);
  // One past the highest id handed out so far (the dump walks the ids below it).
  NodeId idEnd() const;

 private:
  NodeId graph_;
  ThreadId threads_;
  std::vector<NodeId> cuts_;  // thread t starts with the graph nodes [cuts_[t], cuts_[t + 1])
  NodeId createdBase_;                                   // the first id of the first block of created nodes
  unsigned ownerBitsLog_;     // each graph node's owner takes 2^ownerBitsLog_ bits (1 to 16)
  unsigned nodesPerWordLog_;  // 6 - ownerBitsLog_
  std::uint64_t ownerMask_;
  std::unique_ptr<std::atomic<std::uint64_t>[]> owners_;  // threads <= 1024

  unsigned ownerShift(NodeId n) const {
    return unsigned(n & ((1u << nodesPerWordLog_) - 1)) << ownerBitsLog_;
  }
  ThreadId graphOwner(NodeId n) const {
    return ThreadId((owners_[n >> nodesPerWordLog_].load(std::memory_order_relaxed) >> ownerShift(n)) &
                    ownerMask_);
  }
  std::unique_ptr<std::atomic<ThreadId>[]> blockOwner_;
  std::atomic<std::uint32_t> blocks_{0};
};

}  // namespace meldvm::threads
