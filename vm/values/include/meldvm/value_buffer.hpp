// A growing array of values that appends a fact's few arguments without the per-call overhead of
// std::vector's range insert (the Machine buffers every derived and sent fact's arguments in one).
// Values are stored as given: references are the caller's business.
#pragma once

#include <algorithm>
#include <cstdint>

#include "meldvm/native_array.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

class ValueBuffer {
 public:
  // Native code appends to a buffer through its state (native_abi.h's meld_native_array).
  using State = NativeArray<Value>::State;

  std::uint32_t size() const { return std::uint32_t(values_.size()); }
  std::size_t bytesReserved() const { return values_.bytesReserved(); }
  const Value* data() const { return values_.begin(); }
  void clear() { values_.clear(); }
  void reserve(std::size_t n) { values_.reserve(n); }
  // Appends k values; returns the offset of the first.
  std::uint32_t append(const Value* v, std::uint32_t k) {
    const std::uint32_t at = size();
    if (at + k > values_.capacity()) grow(k);
    Value* d = values_.extend(k);
    for (std::uint32_t i = 0; i < k; ++i) d[i] = v[i];
    return at;
  }
  State* forNativeCode() { return values_.forNativeCode(); }

 private:
  [[gnu::noinline]] void grow(std::uint32_t k) {  // out of line: append stays small enough to inline
    values_.reserve(std::max<std::size_t>({values_.capacity() * 2, values_.size() + k, 64}));
  }
  NativeArray<Value> values_;
};

}  // namespace meldvm
