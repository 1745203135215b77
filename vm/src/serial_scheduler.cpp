#include "meldvm/serial_scheduler.hpp"

namespace meldvm {

SerialScheduler::SerialScheduler(const SchedulingOptions& o) : desc_(o.order == PriorityOrder::Desc) {
  noPriority_ = desc_ ? -DBL_MAX : DBL_MAX;
  default_ = o.hasDefaultPriority ? o.defaultPriority : noPriority_;
  // §4.4: the initial priority defaults to the most urgent value.
  initial_ = o.hasInitialPriority ? o.initialPriority : (desc_ ? DBL_MAX : -DBL_MAX);
  if (o.noInitialPriorities) initial_ = default_;
}

void SerialScheduler::start(NodeId nodes) {
  prio_.assign(nodes, initial_);
  defaultPrio_.assign(nodes, default_);
  static_.assign(nodes, 0);
  where_.assign(nodes, Where::Idle);
  heapIndex_.assign(nodes, 0);
  ticket_.assign(nodes, 0);
  for (NodeId n = 0; n < nodes; ++n) wake(n);
}

void SerialScheduler::addNode() {
  prio_.push_back(noPriority_);
  defaultPrio_.push_back(default_);
  static_.push_back(0);
  where_.push_back(Where::Idle);
  heapIndex_.push_back(0);
  ticket_.push_back(0);
}

bool SerialScheduler::pop(NodeId& node) {
  if (!heap_.empty()) {
    node = heap_[0];
    heapRemove(node);
    where_[node] = Where::Idle;
    return true;
  }
  while (fifoHead_ < fifo_.size()) {
    const FifoEntry e = fifo_[fifoHead_++];
    if (where_[e.node] != Where::Fifo || ticket_[e.node] != e.ticket) continue;
    --fifoLive_;
    where_[e.node] = Where::Idle;
    node = e.node;
    if (fifoHead_ > 4096 && fifoHead_ * 2 > fifo_.size()) {
      fifo_.erase(fifo_.begin(), fifo_.begin() + std::ptrdiff_t(fifoHead_));
      fifoHead_ = 0;
    }
    return true;
  }
  return false;
}

void SerialScheduler::wake(NodeId n) {
  if (where_[n] != Where::Idle) return;
  if (prio_[n] != noPriority_) {
    heapPush(n);
  } else {
    where_[n] = Where::Fifo;
    fifo_.push_back({n, ++ticket_[n]});
    ++fifoLive_;
  }
}

void SerialScheduler::finished(NodeId n, bool hasWork) {
  prio_[n] = defaultPrio_[n];
  if (hasWork) wake(n);
}

void SerialScheduler::changed(NodeId n) {
  if (where_[n] == Where::Heap) {
    if (prio_[n] == noPriority_) {  // back to the FIFO
      heapRemove(n);
      where_[n] = Where::Idle;
      wake(n);
    } else {
      siftUp(heapIndex_[n]);
      siftDown(heapIndex_[n]);
    }
  } else if (where_[n] == Where::Fifo && prio_[n] != noPriority_) {
    where_[n] = Where::Idle;  // the FIFO entry goes stale
    --fifoLive_;
    heapPush(n);
  }
}

void SerialScheduler::setPriority(NodeId n, double p) {
  if (!moreUrgent(p, prio_[n])) return;
  prio_[n] = p;
  changed(n);
}

void SerialScheduler::addPriority(NodeId n, double delta) {
  prio_[n] = (prio_[n] == noPriority_ ? 0.0 : prio_[n]) + delta;
  changed(n);
}

void SerialScheduler::removePriority(NodeId n) {
  prio_[n] = defaultPrio_[n];
  changed(n);
}

void SerialScheduler::setDefaultPriority(NodeId n, double p) {
  const bool followsDefault = prio_[n] == defaultPrio_[n];
  defaultPrio_[n] = p;
  if (followsDefault) {
    prio_[n] = p;
    changed(n);
  }
}

void SerialScheduler::scheduleNext(NodeId n) {
  prio_[n] = desc_ ? DBL_MAX : -DBL_MAX;
  changed(n);
}

void SerialScheduler::heapPush(NodeId n) {
  where_[n] = Where::Heap;
  heapIndex_[n] = std::uint32_t(heap_.size());
  heap_.push_back(n);
  siftUp(heapIndex_[n]);
}

void SerialScheduler::heapRemove(NodeId n) {
  const std::uint32_t i = heapIndex_[n];
  const NodeId last = heap_.back();
  heap_.pop_back();
  if (last == n) return;
  heap_[i] = last;
  heapIndex_[last] = i;
  siftDown(i);
  siftUp(heapIndex_[last]);
}

void SerialScheduler::siftUp(std::uint32_t i) {
  while (i > 0) {
    const std::uint32_t parent = (i - 1) / 2;
    if (!moreUrgent(prio_[heap_[i]], prio_[heap_[parent]])) break;
    std::swap(heap_[i], heap_[parent]);
    heapIndex_[heap_[i]] = i;
    heapIndex_[heap_[parent]] = parent;
    i = parent;
  }
}

void SerialScheduler::siftDown(std::uint32_t i) {
  const std::uint32_t size = std::uint32_t(heap_.size());
  for (;;) {
    const std::uint32_t left = 2 * i + 1, right = left + 1;
    std::uint32_t best = i;
    if (left < size && moreUrgent(prio_[heap_[left]], prio_[heap_[best]])) best = left;
    if (right < size && moreUrgent(prio_[heap_[right]], prio_[heap_[best]])) best = right;
    if (best == i) return;
    std::swap(heap_[i], heap_[best]);
    heapIndex_[heap_[i]] = i;
    heapIndex_[heap_[best]] = best;
    i = best;
  }
}

}  // namespace meldvm
