// Which thread (or simulated core) owns which node in a threaded run. The graph's nodes start cut into
// contiguous ranges, one per thread, of about equal weight (a node weighs one plus the facts of its
// axioms), and move when threads steal them; thread t's thread node is N + t; a thread creates nodes (exists)
// from blocks of 16384 ids it takes in turn (§6.10). Read by every thread on every fact it sends: no lock. A
// graph node's owner changes only while every thread waits in the rebalancing barrier (worker.cpp), and a
// block's owner is written before any of its ids can appear in a fact. The graph nodes' owners are
// packed (node_owners.hpp), and the shards read them without a call (graphOwners).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "meldvm/node_owners.hpp"
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
    if (n < graph_) return owners_.owner(n);
    if (n < createdBase_) return n - graph_;  // a thread node
    const std::uint64_t block = (n - createdBase_) / kBlockIds;
    return block < kMaxBlocks ? blockOwner_[block].load(std::memory_order_acquire) : kNoThread;
  }
  // Graph node n now belongs to thread t (only inside the rebalancing barrier, and only by n's
  // owner).
  void moveNode(NodeId n, ThreadId t) { owners_.move(n, t); }
  const NodeOwners& graphOwners() const { return owners_; }
  // A block of ids for nodes thread t creates; throws RuntimeError when ids run out.
  NodeId allocateBlock(ThreadId t, NodeId& count);
  // One past the highest id handed out so far (the dump walks the ids below it).
  NodeId idEnd() const;

 private:
  NodeId graph_;
  ThreadId threads_;
  std::vector<NodeId> cuts_;  // thread t starts with the graph nodes [cuts_[t], cuts_[t + 1])
  NodeId createdBase_;                                   // the first id of the first block of created nodes
  NodeOwners owners_;
  std::unique_ptr<std::atomic<ThreadId>[]> blockOwner_;
  std::atomic<std::uint32_t> blocks_{0};
};

}  // namespace meldvm::threads
