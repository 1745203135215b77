// 4-ary implicit heap. pop() only marks the root as a hole: when the next operation is a push
// (the usual case: a handler schedules the block's next event) the new event fills the hole with a
// single sift-down instead of a sift-down plus a sift-up.
#pragma once

#include <vector>

#include "simcore/future_event_set.hpp"
#include "support/large_allocator.hpp"

namespace simcore {

class HeapFes final : public FutureEventSet {
 public:
  const char* name() const override { return "heap"; }
  void push(const Event& event) override;
  const Event* peek() override;
  void pop() override { rootIsHole_ = true; }
  std::size_t size() const override { return heap_.size() - (rootIsHole_ ? 1 : 0); }
  void clear() override {
    heap_.clear();
    rootIsHole_ = false;
  }

 private:
  void siftDown(std::size_t index, const Event& event);
  void siftUp(std::size_t index, const Event& event);
  void fillHole();

  std::vector<Event, support::LargeAllocator<Event>> heap_;
  bool rootIsHole_ = false;
};

}  // namespace simcore
