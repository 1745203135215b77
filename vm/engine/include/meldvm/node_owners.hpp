// Which thread owns each node of the graph in a threaded run, packed: 2^k bits a node, the fewest
// that hold every thread id (one bit at two threads, 16 at up to 65,536). Every fact a shard sends
// asks for its destination's owner: two bytes a node missed the cache on large graphs (8 % of
// B2 shortest-path's samples at -j 2), and the two calls through ShardLink a fact made took 67
// instructions (posting a local fact takes about 150). The shards read it inline
// (Machine::ownerOf); the owners change only inside a rebalance (vm/threads/worker.cpp), where
// threads give their nodes at the same time.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "meldvm/program.hpp"

namespace meldvm {

class NodeOwners {
 public:
  NodeOwners(NodeId nodes, ThreadId threads)
      : nodes_(nodes),
        bitsLog_(bitsLog(threads)),
        perWordLog_(6 - bitsLog_),
        mask_((std::uint64_t(1) << (1u << bitsLog_)) - 1),
        words_(new std::atomic<std::uint64_t>[(std::size_t(nodes) >> perWordLog_) + 1]) {
    for (std::size_t w = 0; w <= (std::size_t(nodes) >> perWordLog_); ++w)
      words_[w].store(0, std::memory_order_relaxed);
  }

  NodeId size() const { return nodes_; }
  ThreadId owner(NodeId n) const {
    return ThreadId((words_[n >> perWordLog_].load(std::memory_order_relaxed) >> shift(n)) & mask_);
  }
  // Nodes [first, end) start with thread t: before any other thread reads the table, so plain
  // stores (10 million nodes at two threads: 8 ms, against 19 ms with move's atomic per node).
  void assignInitial(NodeId first, NodeId end, ThreadId t) {
    for (NodeId n = first; n < end; ++n) {
      std::atomic<std::uint64_t>& w = words_[n >> perWordLog_];
      const std::uint64_t cleared = w.load(std::memory_order_relaxed) & ~(mask_ << shift(n));
      w.store(cleared | (std::uint64_t(t) << shift(n)), std::memory_order_relaxed);
    }
  }
  // Node n now belongs to t. Only n's owner moves n, but other threads may move other nodes of the
  // same word at the same time: one atomic exclusive-or changes n's bits alone.
  void move(NodeId n, ThreadId t) {
    const std::uint64_t change = std::uint64_t(owner(n) ^ t) << shift(n);
    words_[n >> perWordLog_].fetch_xor(change, std::memory_order_relaxed);
  }

 private:
  static unsigned bitsLog(ThreadId threads) {
    unsigned log = 0;
    while (log < 4 && (std::uint64_t(1) << (1u << log)) < threads) ++log;
    return log;
  }
  unsigned shift(NodeId n) const { return unsigned(n & ((1u << perWordLog_) - 1)) << bitsLog_; }

  NodeId nodes_;
  unsigned bitsLog_;     // a node's owner takes 2^bitsLog_ bits
  unsigned perWordLog_;  // 6 - bitsLog_
  std::uint64_t mask_;
  std::unique_ptr<std::atomic<std::uint64_t>[]> words_;
};

}  // namespace meldvm
