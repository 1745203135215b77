// Calendar queue (R. Brown, 1988): buckets of equal time width forming a circular "year"; each
// bucket is a sorted intrusive list of pool nodes. Expected O(1) per operation when the bucket width
// matches the event density; the queue re-sizes (and re-estimates the width) when the number of
// events doubles or halves. Nodes live in one pool with a free list: no allocation per event.
#pragma once

#include <cstdint>
#include <vector>

#include "simcore/future_event_set.hpp"
#include "support/large_allocator.hpp"

namespace simcore {

class CalendarFes final : public FutureEventSet {
 public:
  CalendarFes();
  const char* name() const override { return "calendar"; }
  void push(const Event& event) override;
  const Event* peek() override;
  void pop() override;
  std::size_t size() const override { return size_; }
  void clear() override;

 private:
  static constexpr std::uint32_t kNil = 0xFFFFFFFFu;
  struct Node {
    Event event;
    std::uint32_t next;
  };

  std::uint32_t bucketOf(SimTime t) const {
    return std::uint32_t(std::uint64_t(t / width_) & (buckets_.size() - 1));
  }
  void insertNode(std::uint32_t node);
  void resize(std::size_t bucketCount);
  SimTime estimateWidth();
  bool locateEarliest();

  std::vector<Node, support::LargeAllocator<Node>> pool_;
  std::uint32_t freeList_ = kNil;
  std::vector<std::uint32_t> tails_;  // last node of each bucket's list
  std::vector<std::uint32_t> buckets_;
  SimTime width_ = 1000;
  std::size_t size_ = 0;
  std::uint32_t current_ = 0;                // bucket of the last located event
  SimTime currentTop_ = 0;                   // end (exclusive) of the current bucket's window in this year
  std::uint32_t located_ = kNil;             // bucket whose head is the earliest event (valid after peek)
  std::uint64_t operations_ = 0, work_ = 0;  // list steps and empty buckets seen since the last review
  std::vector<SimTime> sample_;              // scratch for width estimation
  std::vector<std::uint32_t> scratchNodes_;  // scratch for resizing
};

}  // namespace simcore
