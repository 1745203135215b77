#include "meldvm/serial_scheduler.hpp"

namespace meldvm {

SerialScheduler::SerialScheduler(const SchedulingOptions& o) : desc_(o.order == PriorityOrder::Desc) {
  noPriority_ = o.hasNoPriority ? o.noPriority : (desc_ ? -DBL_MAX : DBL_MAX);
  default_ = o.hasDefaultPriority ? o.defaultPriority : noPriority_;
  // §4.4: the initial priority defaults to the most urgent value.
  initial_ = o.hasInitialPriority ? o.initialPriority : (desc_ ? DBL_MAX : -DBL_MAX);
  if (o.noInitialPriorities) initial_ = default_;
}

void SerialScheduler::start(NodeId nodes, NodeId first, NodeId end) {
  NodeState init;
  init.prio = initial_;
  init.defaultPrio = default_;
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

bool SerialScheduler::pop(NodeId& node) {
  if (!heap_.empty()) {
    node = heap_[0];
    heapRemove(node);
    nodes_[node].where = Where::Idle;
    return true;
  }
  while (fifoHead_ < fifo_.size()) {
    const FifoEntry e = fifo_[fifoHead_++];
    if (nodes_[e.node].where != Where::Fifo || nodes_[e.node].ticket != e.ticket) continue;
    --fifoLive_;
    nodes_[e.node].where = Where::Idle;
    node = e.node;
    if (fifoHead_ > 4096 && fifoHead_ * 2 > fifo_.size()) {
      fifo_.erase(fifo_.begin(), fifo_.begin() + std::ptrdiff_t(fifoHead_));
      fifoHead_ = 0;
    }
    return true;
  }
  return false;
}

void SerialScheduler::enqueue(NodeId n) {
  if (nodes_[n].prio != noPriority_) {
    heapPush(n);
  } else {
    nodes_[n].where = Where::Fifo;
    fifo_.push_back({n, ++nodes_[n].ticket});
    ++fifoLive_;
  }
}

void SerialScheduler::finished(NodeId n, bool hasWork) {
  nodes_[n].prio = nodes_[n].defaultPrio;
  if (hasWork) wake(n);
}

void SerialScheduler::changed(NodeId n) {
  if (nodes_[n].where == Where::Heap) {
    if (nodes_[n].prio == noPriority_) {  // back to the FIFO
      heapRemove(n);
      nodes_[n].where = Where::Idle;
      wake(n);
    } else {
      siftUp(nodes_[n].heapIndex);
      siftDown(nodes_[n].heapIndex);
    }
  } else if (nodes_[n].where == Where::Fifo && nodes_[n].prio != noPriority_) {
    nodes_[n].where = Where::Idle;  // the FIFO entry goes stale
    --fifoLive_;
    heapPush(n);
  }
}

void SerialScheduler::setPriority(NodeId n, double p) {
  if (!moreUrgent(p, nodes_[n].prio)) return;
  nodes_[n].prio = p;
  changed(n);
}

void SerialScheduler::addPriority(NodeId n, double delta) {
  // Plain addition, as the established VM: "no priority" (-DBL_MAX, +DBL_MAX for asc) absorbs
  // any small delta, so a node without a priority keeps none.
  nodes_[n].prio += delta;
  changed(n);
}

void SerialScheduler::removePriority(NodeId n) {
  nodes_[n].prio = nodes_[n].defaultPrio;
  changed(n);
}

void SerialScheduler::setDefaultPriority(NodeId n, double p) {
  const bool followsDefault = nodes_[n].prio == nodes_[n].defaultPrio;
  nodes_[n].defaultPrio = p;
  if (followsDefault) {
    nodes_[n].prio = p;
    changed(n);
  }
}

void SerialScheduler::scheduleNext(NodeId n) {
  nodes_[n].prio = desc_ ? DBL_MAX : -DBL_MAX;
  changed(n);
}

void SerialScheduler::heapPush(NodeId n) {
  nodes_[n].where = Where::Heap;
  nodes_[n].heapIndex = std::uint32_t(heap_.size());
  heap_.push_back(n);
  siftUp(nodes_[n].heapIndex);
}

void SerialScheduler::heapRemove(NodeId n) {
  const std::uint32_t i = nodes_[n].heapIndex;
  const NodeId last = heap_.back();
  heap_.pop_back();
  if (last == n) return;
  heap_[i] = last;
  nodes_[last].heapIndex = i;
  siftDown(i);
  siftUp(nodes_[last].heapIndex);
}

void SerialScheduler::siftUp(std::uint32_t i) {
  while (i > 0) {
    const std::uint32_t parent = (i - 1) / 2;
    if (!moreUrgent(nodes_[heap_[i]].prio, nodes_[heap_[parent]].prio)) break;
    std::swap(heap_[i], heap_[parent]);
    nodes_[heap_[i]].heapIndex = i;
    nodes_[heap_[parent]].heapIndex = parent;
    i = parent;
  }
}

void SerialScheduler::siftDown(std::uint32_t i) {
  const std::uint32_t size = std::uint32_t(heap_.size());
  for (;;) {
    const std::uint32_t left = 2 * i + 1, right = left + 1;
    std::uint32_t best = i;
    if (left < size && moreUrgent(nodes_[heap_[left]].prio, nodes_[heap_[best]].prio)) best = left;
    if (right < size && moreUrgent(nodes_[heap_[right]].prio, nodes_[heap_[best]].prio)) best = right;
    if (best == i) return;
    std::swap(heap_[i], heap_[best]);
    nodes_[heap_[i]].heapIndex = i;
    nodes_[heap_[best]].heapIndex = best;
    i = best;
  }
}

}  // namespace meldvm
