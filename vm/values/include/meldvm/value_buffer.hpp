// A growing array of values that appends a fact's few arguments without the per-call overhead of
// std::vector's range insert (the Machine buffers every derived and sent fact's arguments in one).
// Values are stored as given: references are the caller's business.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "meldvm/value.hpp"

namespace meldvm {

class ValueBuffer {
 public:
  std::uint32_t size() const { return size_; }
  std::size_t bytesReserved() const { return store_.capacity() * sizeof(Value); }
  const Value* data() const { return store_.data(); }
  void clear() { size_ = 0; }
  void reserve(std::size_t n) {
    if (n > store_.size()) store_.resize(n);
  }
  // Appends k values; returns the offset of the first.
  std::uint32_t append(const Value* v, std::uint32_t k) {
    if (size_ + k > store_.size()) grow(k);
    Value* d = store_.data() + size_;
    for (std::uint32_t i = 0; i < k; ++i) d[i] = v[i];
    const std::uint32_t at = size_;
    size_ += k;
    return at;
  }

 private:
  [[gnu::noinline]] void grow(std::uint32_t k) {  // out of line: append stays small enough to inline
    store_.resize(std::max<std::size_t>({store_.size() * 2, std::size_t(size_) + k, 64}));
  }
  std::vector<Value> store_;  // its size is the capacity
  std::uint32_t size_ = 0;
};

}  // namespace meldvm
