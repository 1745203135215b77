#include "meldvm/serial_scheduler.hpp"

#include <utility>

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
  nodes_ = NodePages<NodeState, 1>(1, init);
  nodes_.addNodes(nodes);
  for (NodeId n = first; n < end; ++n) {
    at(n).held = 1;
    wake(n);
  }
}

void SerialScheduler::addNode() {
  nodes_.addNodes(1);
  // Unwritten records read as the initial state; a created node differs only when "no
  // priority" is not the initial priority (writing it allocates the node's page).
  if (noPriority_ != initial_) at(NodeId(nodes_.nodes() - 1)).prio = noPriority_;
}

bool SerialScheduler::pop(NodeId& node) {
  if (!heap_.empty()) {
    node = heap_[0];
    heapRemove(node);
    at(node).where = Where::Idle;
    return true;
  }
  while (fifoHead_ < fifo_.size()) {
    const FifoEntry e = fifo_[fifoHead_++];
    const NodeState& seen = std::as_const(*this).at(e.node);  // stale entries write nothing
    if (seen.where != Where::Fifo || seen.ticket != e.ticket) continue;
    --fifoLive_;
    at(e.node).where = Where::Idle;
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
  NodeState& s = at(n);
  if (s.prio != noPriority_) {
    heapPush(n);
  } else {
    s.where = Where::Fifo;
    fifo_.push_back({n, ++s.ticket});
    ++fifoLive_;
  }
}

void SerialScheduler::finished(NodeId n, bool hasWork) {
  NodeState& s = at(n);
  s.prio = s.defaultPrio;
  if (hasWork && s.where == Where::Idle) enqueue(n);
}

void SerialScheduler::changed(NodeId n) {
  if (at(n).where == Where::Heap) {
    if (at(n).prio == noPriority_) {  // back to the FIFO
      heapRemove(n);
      at(n).where = Where::Idle;
      wake(n);
    } else {
      siftUp(at(n).heapIndex);
      siftDown(at(n).heapIndex);
    }
  } else if (at(n).where == Where::Fifo && at(n).prio != noPriority_) {
    at(n).where = Where::Idle;  // the FIFO entry goes stale
    --fifoLive_;
    heapPush(n);
  }
}

void SerialScheduler::setPriority(NodeId n, double p) {
  if (!moreUrgent(p, at(n).prio)) return;
  at(n).prio = p;
  changed(n);
}

void SerialScheduler::addPriority(NodeId n, double delta) {
  // Plain addition, as the established VM: "no priority" (-DBL_MAX, +DBL_MAX for asc) absorbs
  // any small delta, so a node without a priority keeps none.
  at(n).prio += delta;
  changed(n);
}

void SerialScheduler::removePriority(NodeId n) {
  at(n).prio = at(n).defaultPrio;
  changed(n);
}

void SerialScheduler::setDefaultPriority(NodeId n, double p) {
  const bool followsDefault = at(n).prio == at(n).defaultPrio;
  at(n).defaultPrio = p;
  if (followsDefault) {
    at(n).prio = p;
    changed(n);
  }
}

void SerialScheduler::scheduleNext(NodeId n) {
  at(n).prio = desc_ ? DBL_MAX : -DBL_MAX;
  changed(n);
}

void SerialScheduler::heapPush(NodeId n) {
  NodeState& s = at(n);
  s.where = Where::Heap;
  s.heapIndex = std::uint32_t(heap_.size());
  heap_.push_back(n);
  siftUp(s.heapIndex);
}

void SerialScheduler::heapRemove(NodeId n) {
  const std::uint32_t i = at(n).heapIndex;
  const NodeId last = heap_.back();
  heap_.pop_back();
  if (last == n) return;
  heap_[i] = last;
  at(last).heapIndex = i;
  siftDown(i);
  siftUp(at(last).heapIndex);
}

void SerialScheduler::siftUp(std::uint32_t i) {
  while (i > 0) {
    const std::uint32_t parent = (i - 1) / 2;
    if (!moreUrgent(priority(heap_[i]), priority(heap_[parent]))) break;
    std::swap(heap_[i], heap_[parent]);
    at(heap_[i]).heapIndex = i;
    at(heap_[parent]).heapIndex = parent;
    i = parent;
  }
}

void SerialScheduler::siftDown(std::uint32_t i) {
  const std::uint32_t size = std::uint32_t(heap_.size());
  for (;;) {
    const std::uint32_t left = 2 * i + 1, right = left + 1;
    std::uint32_t best = i;
    if (left < size && moreUrgent(priority(heap_[left]), priority(heap_[best]))) best = left;
    if (right < size && moreUrgent(priority(heap_[right]), priority(heap_[best]))) best = right;
    if (best == i) return;
    std::swap(heap_[i], heap_[best]);
    at(heap_[i]).heapIndex = i;
    at(heap_[best]).heapIndex = best;
    i = best;
  }
}

}  // namespace meldvm
