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
  // Where the values are, how many, room for how many: native code appends to a buffer through
  // this (native_abi.h's meld_native_array), calling the VM only when it is full.
  struct State {
    Value* data = nullptr;
    std::uint32_t size = 0;
    std::uint32_t capacity = 0;
  };

  ValueBuffer() = default;
  ValueBuffer(const ValueBuffer&) = delete;  // native code may hold the state's address
  ValueBuffer& operator=(const ValueBuffer&) = delete;

  std::uint32_t size() const { return state_.size; }
  std::size_t bytesReserved() const { return store_.capacity() * sizeof(Value); }
  const Value* data() const { return state_.data; }
  void clear() { state_.size = 0; }
  void reserve(std::size_t n) {
    if (n > state_.capacity) resize(n);
  }
  // Appends k values; returns the offset of the first.
  std::uint32_t append(const Value* v, std::uint32_t k) {
    if (state_.size + k > state_.capacity) grow(k);
    Value* d = state_.data + state_.size;
    for (std::uint32_t i = 0; i < k; ++i) d[i] = v[i];
    const std::uint32_t at = state_.size;
    state_.size += k;
    return at;
  }
  State* forNativeCode() { return &state_; }

 private:
  [[gnu::noinline]] void grow(std::uint32_t k) {  // out of line: append stays small enough to inline
    resize(std::max<std::size_t>({store_.size() * 2, std::size_t(state_.size) + k, 64}));
  }
  void resize(std::size_t n) {
    store_.resize(n);
    state_.data = store_.data();
    state_.capacity = std::uint32_t(n);
  }
  std::vector<Value> store_;  // its size is the capacity
  State state_{};
};

}  // namespace meldvm
