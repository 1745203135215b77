#include "meldvm/serial_scheduler.hpp"

namespace meldvm {

SerialScheduler::SerialScheduler(const SchedulingOptions& o) : desc_(o.order == PriorityOrder::Desc) {
  noPriority_ = o.hasNoPriority ? o.noPriority : (desc_ ? -DBL_MAX : DBL_MAX);
  default_ = o.hasDefaultPriority ? o.defaultPriority : noPriority_;
  // §4.4: the initial priority defaults to the most urgent value.
  initial_ = o.hasInitialPriority ? o.initialPriority : mostUrgent();
  if (o.noInitialPriorities) initial_ = default_;
}

void SerialScheduler::start(NodeId nodes, NodeId first, NodeId end) {
  NodeState init;
  init.prio = initial_;
  init.defaultPrio = default_;
  nodes_.reserve(nodes);
  support::prefault(nodes_.data(), std::size_t(nodes) * sizeof(NodeState));  // all written now
  nodes_.assign(nodes, init);
  for (NodeId n = first; n < end; ++n) {
    nodes_[n].held = 1;
    wake(n);
  }
}

void SerialScheduler::addNode() {
  NodeState fresh;
  fresh.prio = noPriority_;
  fresh.defaultPrio = default_;
  nodes_.push_back(fresh);
}

NodeId SerialScheduler::popHeap() {
  const NodeId node = heap_[0];
  heapRemove(node);
  nodes_[node].where = Where::Idle;
  return node;
}

void SerialScheduler::dropServedEntries() {
  fifo_.erase(fifo_.begin(), fifo_.begin() + std::ptrdiff_t(fifoHead_));
  fifoHead_ = 0;
}

void SerialScheduler::finished(NodeId n, bool hasWork) {
  nodes_[n].prio = nodes_[n].defaultPrio;
  if (hasWork) wake(n);
}

// The established VM's do_set_node_priority: the priority only ever becomes more urgent here; a
// node in the heap moves when it did; a node in the FIFO always leaves it for the heap, with
// whatever priority it has now ("no priority" included: such a node then still runs before the
// FIFO); an idle node keeps the priority for when work arrives, or, for schedule-next, is queued
// at once.
void SerialScheduler::raise(NodeId n, double p, bool queueIdle) {
  NodeState& s = nodes_[n];
  const double old = s.prio;
  const bool raised = moreUrgent(p, old);
  if (raised) s.prio = p;
  switch (s.where) {
    case Where::Heap:
      if (raised) siftUp(s.heapIndex);  // more urgent: it can only move up
      break;
    case Where::Fifo:
      s.where = Where::Idle;  // its FIFO entry goes stale
      --fifoLive_;
      heapPush(n);
      break;
    case Where::Idle:
      if (queueIdle) enqueue(n);
      break;
  }
}

void SerialScheduler::setPriority(NodeId n, double p) {
  if (moreUrgent(p, nodes_[n].prio)) raise(n, p, false);
}

void SerialScheduler::addPriority(NodeId n, double delta) {
  // Plain addition, as the established VM: "no priority" (-DBL_MAX, +DBL_MAX for asc) absorbs
  // any small delta, and a less urgent sum changes nothing (but still moves a node of the FIFO).
  raise(n, nodes_[n].prio + delta, false);
}

void SerialScheduler::removePriority(NodeId n) {
  // Back to the default, and a node of the heap goes to the end of the FIFO, whatever its default.
  nodes_[n].prio = nodes_[n].defaultPrio;
  if (nodes_[n].where != Where::Heap) return;
  heapRemove(n);
  fifoPush(n);
}

// Only the default changes: a node takes it when its next run ends (finished).
void SerialScheduler::setDefaultPriority(NodeId n, double p) { nodes_[n].defaultPrio = p; }

void SerialScheduler::scheduleNext(NodeId n) { raise(n, mostUrgent(), true); }

void SerialScheduler::heapPush(NodeId n) {
  nodes_[n].where = Where::Heap;
  nodes_[n].heapIndex = std::uint32_t(heap_.size());
  heap_.push_back(n);
  siftUp(nodes_[n].heapIndex);
}

// The heap works as the established VM's, ties included, since the order of nodes of equal
// priority is observable: a node taken out is replaced by the last one, which moves up only when
// it is strictly more urgent than its new parent and otherwise down (so it stays put when it
// equals its parent); going down, a node stops when it is as urgent as both children, and of two
// equally urgent children takes the right one.
void SerialScheduler::heapRemove(NodeId n) {
  const std::uint32_t i = nodes_[n].heapIndex;
  const NodeId last = heap_.back();
  heap_.pop_back();
  if (last == n) return;
  heap_[i] = last;
  nodes_[last].heapIndex = i;
  if (i > 0 && asUrgent(nodes_[last].prio, nodes_[heap_[(i - 1) / 2]].prio))
    siftUp(i);
  else
    siftDown(i);
}

void SerialScheduler::siftUp(std::uint32_t i) {
  while (i > 0) {
    const std::uint32_t parent = (i - 1) / 2;
    if (!moreUrgent(nodes_[heap_[i]].prio, nodes_[heap_[parent]].prio)) break;
    swapEntries(i, parent);
    i = parent;
  }
}

void SerialScheduler::siftDown(std::uint32_t i) {
  const std::uint32_t size = std::uint32_t(heap_.size());
  auto prio = [&](std::uint32_t k) { return nodes_[heap_[k]].prio; };
  for (;;) {
    const std::uint32_t left = 2 * i + 1, right = left + 1;
    if (left >= size) return;
    const bool hasRight = right < size;
    if (asUrgent(prio(i), prio(left)) && (!hasRight || asUrgent(prio(i), prio(right)))) return;
    const std::uint32_t next = hasRight && asUrgent(prio(right), prio(left)) ? right : left;
    swapEntries(i, next);
    i = next;
  }
}

void SerialScheduler::swapEntries(std::uint32_t a, std::uint32_t b) {
  std::swap(heap_[a], heap_[b]);
  nodes_[heap_[a]].heapIndex = a;
  nodes_[heap_[b]].heapIndex = b;
}

}  // namespace meldvm
