// The serial node scheduler of the established VM (spec §6.11, one thread): nodes wait in a
// priority heap (when their priority differs from "no priority") or in a FIFO; the heap is served
// first. The heap is a plain binary heap that never swaps equal keys, which is what makes the
// start-up order 0, N-1, N-2, ..., 1 when every node has the same initial priority [quirk].
#pragma once

#include <cfloat>
#include <cstdint>
#include <vector>

#include "meldvm/large_allocator.hpp"
#include "meldvm/program.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

class SerialScheduler {
 public:
  explicit SerialScheduler(const SchedulingOptions& options);

  // Called once with the initial node count, before any run: the nodes [first, end) (all of them
  // in a serial run, a shard's own in a threaded one) are queued in id order.
  void start(NodeId nodes, NodeId first, NodeId end);
  // A node created at run time (exists): it starts with no priority.
  void addNode();
  // A deleted created node's id is used again: the node starts afresh (it waits nowhere).
  void renewNode(NodeId n) {
    nodes_[n].prio = noPriority_;
    nodes_[n].defaultPrio = default_;
    nodes_[n].isStatic = 0;
  }

  // The next node to run (heap first, then FIFO), or false when none is waiting. (The FIFO's
  // case inline, as wake's: the calls of pop, enqueue and fifoPush were 2 % of heat-transfer's
  // native instructions.)
  bool pop(NodeId& node) {
    if (!heap_.empty()) {
      node = popHeap();
      return true;
    }
    while (fifoHead_ < fifo_.size()) {
      const FifoEntry e = fifo_[fifoHead_++];
      if (nodes_[e.node].where != Where::Fifo || nodes_[e.node].ticket != e.ticket) continue;
      --fifoLive_;
      nodes_[e.node].where = Where::Idle;
      node = e.node;
      if (fifoHead_ > 4096 && fifoHead_ * 2 > fifo_.size()) [[unlikely]]
        dropServedEntries();
      return true;
    }
    return false;
  }
  // The node received work while not running: queue it unless it already waits.
  void wake(NodeId n) {  // inline: most wake-ups find the node already waiting
    if (nodes_[n].where == Where::Idle) enqueue(n);
  }
  // The node that pop() will return after the next `ahead` pops, when it is already known (the
  // FIFO is served and holds that many nodes); false otherwise. For prefetching only.
  bool peek(std::size_t ahead, NodeId& node) const {
    if (!heap_.empty()) return false;
    const std::size_t i = fifoHead_ + ahead;
    if (i >= fifo_.size()) return false;
    node = fifo_[i].node;  // may be a stale entry: harmless for a hint
    return true;
  }
  // The node's run ended: its temporary priority falls back to the default; requeue if it still
  // has work.
  void finished(NodeId n, bool hasWork);

  // §5.7 coordination (the running node's own requests are filtered out by the caller).
  void setPriority(NodeId n, double p);  // raise only if more urgent
  void addPriority(NodeId n, double delta);
  void removePriority(NodeId n);
  void setDefaultPriority(NodeId n, double p);
  void scheduleNext(NodeId n);
  // schedule-next of the node that runs: the most urgent priority until its run ends (finished).
  void scheduleRunning(NodeId n) { nodes_[n].prio = mostUrgent(); }
  void setStatic(NodeId n, bool isStatic) { nodes_[n].isStatic = isStatic; }

  // Work stealing (a threaded run): the waiting nodes (heap and FIFO) that `movable(n)` allows
  // and are not static, appended to `out` (they stay queued).
  template <class Movable>
  void queuedForSteal(std::vector<NodeId>& out, Movable&& movable) const {
    for (NodeId n : heap_)
      if (!nodes_[n].isStatic && movable(n)) out.push_back(n);
    for (std::size_t i = fifoHead_; i < fifo_.size(); ++i) {
      const FifoEntry e = fifo_[i];
      const NodeState& s = nodes_[e.node];
      if (s.where == Where::Fifo && s.ticket == e.ticket && !s.isStatic && movable(e.node))
        out.push_back(e.node);
    }
  }
  // Takes the node out of the queue, wherever it waits (set-cpu moves it to another thread).
  void unqueue(NodeId n) {
    NodeState& s = nodes_[n];
    if (s.where == Where::Heap) heapRemove(n);
    if (s.where == Where::Fifo) --fifoLive_;  // its entry goes stale
    s.where = Where::Idle;
  }
  // A node's scheduling state, carried along when it moves to another thread.
  struct Carried {
    double prio, defaultPrio;
    bool isStatic;
  };
  Carried carried(NodeId n) const { return {nodes_[n].prio, nodes_[n].defaultPrio, nodes_[n].isStatic != 0}; }
  void adopt(NodeId n, const Carried& c) {
    nodes_[n].prio = c.prio;
    nodes_[n].defaultPrio = c.defaultPrio;
    nodes_[n].isStatic = c.isStatic;
    nodes_[n].held = 1;
  }
  void letGo(NodeId n) { nodes_[n].held = 0; }
  // The node is one of the graph's nodes queued at start() or adopted since, and not given away
  // since: its facts are here. Unlike the owner table, which another thread changes while a
  // rebalance hands nodes over, this shard alone changes it.
  bool held(NodeId n) const { return nodes_[n].held != 0; }

  double priority(NodeId n) const { return nodes_[n].prio; }
  bool isStatic(NodeId n) const { return nodes_[n].isStatic != 0; }
  bool waiting(NodeId n) const { return nodes_[n].where != Where::Idle; }
  // A hint that `wake(n)` comes soon (always inlined: GCC drops calls to prefetch-only functions).
  [[gnu::always_inline]] void prefetch(NodeId n) const { __builtin_prefetch(&nodes_[n]); }
  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t bytesReserved() const {
    return nodes_.capacity() * sizeof(NodeState) + heap_.capacity() * sizeof(NodeId) +
           fifo_.capacity() * sizeof(FifoEntry);
  }
  std::size_t waiting() const { return heap_.size() + fifoLive_; }
  // Urgency order: true when a is strictly more urgent than b.
  bool moreUrgent(double a, double b) const { return desc_ ? a > b : a < b; }
  bool asUrgent(double a, double b) const { return desc_ ? a >= b : a <= b; }  // at least as urgent
  double mostUrgent() const { return desc_ ? DBL_MAX : -DBL_MAX; }
  double noPriority() const { return noPriority_; }

 private:
  enum class Where : std::uint8_t { Idle, Fifo, Heap };

  void enqueue(NodeId n) {  // an idle node becomes runnable
    if (nodes_[n].prio != noPriority_)
      heapPush(n);
    else
      fifoPush(n);
  }
  void fifoPush(NodeId n) {
    nodes_[n].where = Where::Fifo;
    fifo_.push_back({n, ++nodes_[n].ticket});
    ++fifoLive_;
  }
  NodeId popHeap();  // the heap's first node, out of the heap
  void dropServedEntries();
  void heapPush(NodeId n);
  void heapRemove(NodeId n);
  void siftUp(std::uint32_t i);
  void siftDown(std::uint32_t i);
  void raise(NodeId n, double p, bool queueIdle);  // p if more urgent; FIFO/heap moves
  void swapEntries(std::uint32_t a, std::uint32_t b);

  bool desc_;
  double noPriority_, initial_, default_;
  // Everything the scheduler keeps per node in one record: a wake-up touches one cache line.
  struct NodeState {
    double prio, defaultPrio;
    std::uint32_t heapIndex = 0, ticket = 0;
    Where where = Where::Idle;
    std::uint8_t isStatic = 0;
    std::uint8_t held = 0;  // a threaded run: the node's facts are in this shard (see held())
  };
  LargeVector<NodeState> nodes_;
  std::vector<NodeId> heap_;
  // A node may leave the FIFO for the heap (a priority was set): its entry then goes stale, which
  // the ticket detects. Consumed from fifoHead_, compacted when the dead prefix is large.
  struct FifoEntry {
    NodeId node;
    std::uint32_t ticket;
  };
  std::vector<FifoEntry> fifo_;
  std::size_t fifoHead_ = 0, fifoLive_ = 0;
};

}  // namespace meldvm
