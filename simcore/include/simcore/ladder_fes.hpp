// A two-tier ladder queue (after Tang, Goh and Thng, 2005): far-future events are appended unsorted
// to "top"; when the rung of buckets in use runs out, top is spread over a new rung whose bucket
// width is chosen from top's span and size (about kTargetPerBucket events a bucket); a bucket is
// sorted only when dequeueing reaches it. Inserting is an append to one of a few
// thousand bucket tails (cache resident) and dequeueing walks contiguous memory, which is what makes
// it fast with a million pending events. Bucket capacities are kept: no allocation in steady state.
#pragma once

#include <cstdint>
#include <vector>

#include "simcore/future_event_set.hpp"
#include "support/large_allocator.hpp"

namespace simcore {

class LadderFes final : public FutureEventSet {
 public:
  const char* name() const override { return "ladder"; }
  void push(const Event& event) override;
  const Event* peek() override;
  void pop() override;
  const Event* peekAhead(std::size_t k) override {
    return k < current_.size() ? &current_[current_.size() - 1 - k] : nullptr;
  }
  std::size_t size() const override { return size_; }
  void clear() override;

 private:
  static constexpr std::size_t kTargetPerBucket = 128;
  static constexpr std::size_t kMaxBuckets = std::size_t(1) << 20;

  bool advance();
  void rebuildRung();

  // Current bucket: events with time < currentEnd_, sorted latest first (the next one is at the back).
  std::vector<Event> current_;
  SimTime currentEnd_ = 0;
  // The rung: bucket i holds events with time in [rungStart_ + i*width_, rungStart_ + (i+1)*width_).
  std::vector<std::vector<Event>> buckets_;
  std::size_t rungBuckets_ = 0;  // buckets in use (buckets_ may hold more, kept for their capacity)
  std::size_t nextBucket_ = 0;   // first bucket not yet moved to current_
  SimTime rungStart_ = 0;
  SimTime rungEnd_ = 0;
  SimTime width_ = 1;
  // Top: unsorted events with time >= rungEnd_.
  std::vector<Event, support::LargeAllocator<Event>> top_;
  SimTime topMin_ = kTimeInfinity, topMax_ = 0;
  std::size_t size_ = 0;
};

}  // namespace simcore
