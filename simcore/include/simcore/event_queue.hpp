// The kernel's queue: a FIFO per priority class for events scheduled at the current time, in front
// of a future-event set for later ones. Most notifications (neighbor changes, immediate sends) are
// scheduled "now"; they never touch the heap or calendar.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "simcore/future_event_set.hpp"

namespace simcore {

// A growable ring buffer; capacity is kept, so steady-state use does not allocate.
class EventRing {
 public:
  bool empty() const { return head_ == tail_; }
  std::size_t size() const { return tail_ - head_; }
  const Event& front() const { return slots_[head_ & mask_]; }
  void popFront() { ++head_; }
  void pushBack(const Event& e) {
    if (size() == slots_.size()) grow();
    slots_[tail_ & mask_] = e;
    ++tail_;
  }
  void clear() { head_ = tail_ = 0; }

 private:
  void grow() {
    std::vector<Event> bigger(slots_.empty() ? 64 : slots_.size() * 2);
    for (std::size_t i = 0; i < size(); ++i) bigger[i] = slots_[(head_ + i) & mask_];
    tail_ = size();
    head_ = 0;
    slots_.swap(bigger);
    mask_ = slots_.size() - 1;
  }
  std::vector<Event> slots_;
  std::size_t head_ = 0, tail_ = 0, mask_ = 0;
};

class EventQueue {
 public:
  explicit EventQueue(std::unique_ptr<FutureEventSet> fes) : fes_(std::move(fes)) {}

  SimTime now() const { return now_; }
  std::uint64_t nextSequence() const { return sequence_; }
  FutureEventSet& futureEventSet() { return *fes_; }

  // Schedules an event; `time` must not be earlier than now(). `bypassFifo` sends an event due now
  // to the future-event set anyway (for bulk scheduling, so the FIFO does not grow to hold them all).
  void schedule(SimTime time, PriorityClass cls, std::uint32_t block, EventKind kind, std::uint8_t face,
                std::uint64_t arg, bool bypassFifo = false) {
    Event e;
    e.time = time;
    e.order = (std::uint64_t(cls) << Event::kSequenceBits) | sequence_++;
    e.block = block;
    e.kind = kind;
    e.face = face;
    e.arg = arg;
    if (time == now_ && !bypassFifo) {
      rings_[std::size_t(cls)].pushBack(e);
      nonEmptyRings_ |= 1u << unsigned(cls);
    } else {
      fes_->push(e);
    }
    if (++count_ > maxSize_) maxSize_ = count_;
  }

  // Removes the earliest event into `out`; false when nothing is pending or the earliest is later
  // than `limit` (then nothing is removed).
  bool popUntil(SimTime limit, Event& out) {
    if (nonEmptyRings_) {
      // Ring events are at now_: only a future-event-set event at now_ with a smaller order wins.
      const unsigned cls = unsigned(__builtin_ctz(nonEmptyRings_));
      EventRing& ring = rings_[cls];
      const Event* f = fes_->peek();
      if (f && f->time == now_ && f->order < ring.front().order) {
        out = *f;
        fes_->pop();
        --count_;
        return true;
      }
      if (now_ > limit) return false;
      out = ring.front();
      ring.popFront();
      --count_;
      if (ring.empty()) nonEmptyRings_ &= ~(1u << cls);
      return true;
    }
    const Event* f = fes_->peek();
    if (!f || f->time > limit) return false;
    out = *f;
    fes_->pop();
    --count_;
    now_ = out.time;
    return true;
  }

  // A hint of an event coming soon (about k events ahead, after those due now), or nullptr; for
  // prefetching only.
  const Event* peekAhead(std::size_t k) { return fes_->peekAhead(k); }

  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; }
  std::size_t maxSize() const { return maxSize_; }
  // Next event time, or kTimeInfinity.
  SimTime nextTime() {
    if (nonEmptyRings_) return now_;
    const Event* f = fes_->peek();
    return f ? f->time : kTimeInfinity;
  }
  void advanceTo(SimTime t) {
    if (t > now_ && nonEmptyRings_ == 0) now_ = t;
  }

 private:
  std::unique_ptr<FutureEventSet> fes_;
  std::array<EventRing, kPriorityClassCount> rings_;
  unsigned nonEmptyRings_ = 0;
  SimTime now_ = 0;
  std::uint64_t sequence_ = 0;
  std::size_t count_ = 0;
  std::size_t maxSize_ = 0;
};

}  // namespace simcore
