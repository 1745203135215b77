#include "simcore/heap_fes.hpp"

namespace simcore {

void HeapFes::siftDown(std::size_t index, const Event& event) {
  const std::size_t n = heap_.size();
  Event* h = heap_.data();
  for (;;) {
    const std::size_t first = 4 * index + 1;
    if (first >= n) break;
    std::size_t best = first;
    const std::size_t last = first + 4 < n ? first + 4 : n;
    for (std::size_t c = first + 1; c < last; ++c)
      if (earlier(h[c], h[best])) best = c;
    if (!earlier(h[best], event)) break;
    h[index] = h[best];
    index = best;
  }
  h[index] = event;
}

void HeapFes::siftUp(std::size_t index, const Event& event) {
  Event* h = heap_.data();
  while (index > 0) {
    const std::size_t parent = (index - 1) / 4;
    if (!earlier(event, h[parent])) break;
    h[index] = h[parent];
    index = parent;
  }
  h[index] = event;
}

void HeapFes::fillHole() {
  rootIsHole_ = false;
  const Event last = heap_.back();
  heap_.pop_back();
  if (!heap_.empty()) siftDown(0, last);
}

void HeapFes::push(const Event& event) {
  if (rootIsHole_) {
    rootIsHole_ = false;
    siftDown(0, event);
    return;
  }
  heap_.push_back(event);
  siftUp(heap_.size() - 1, event);
}

const Event* HeapFes::peek() {
  if (rootIsHole_) fillHole();
  return heap_.empty() ? nullptr : &heap_[0];
}

}  // namespace simcore
