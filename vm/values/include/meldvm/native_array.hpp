// A growing array whose state (where it is, how many elements, room for how many) is a plain
// struct that native code appends to without a call (native_abi.h's meld_native_array), calling
// the VM only when the array is full. The Machine's buffers that native code fills are these, and
// the ValueBuffers of their arguments are built on one.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <vector>

#include "meldvm/large_allocator.hpp"

namespace meldvm {

template <class T>
class NativeArray {
 public:
  struct State {  // meld_native_array's layout
    T* data = nullptr;
    std::uint32_t size = 0;
    std::uint32_t capacity = 0;
  };

  NativeArray() = default;
  NativeArray(const NativeArray&) = delete;  // native code holds the state's address
  NativeArray& operator=(const NativeArray&) = delete;

  void push_back(const T& v) {
    if (state_.size == state_.capacity) [[unlikely]]
      grow(1);
    state_.data[state_.size++] = v;
  }
  // Room for n elements in all, exactly (no more than n is taken when the array grows here).
  void reserve(std::size_t n) {
    if (n > state_.capacity) resize(n);
  }
  // k more elements, uninitialised, at the end (there must be room: reserve first); their start.
  T* extend(std::uint32_t k) {
    T* at = state_.data + state_.size;
    state_.size += k;
    return at;
  }
  std::size_t size() const { return state_.size; }
  bool empty() const { return state_.size == 0; }
  std::size_t capacity() const { return state_.capacity; }
  const T& operator[](std::size_t i) const { return state_.data[i]; }
  T& operator[](std::size_t i) { return state_.data[i]; }
  const T* begin() const { return state_.data; }
  const T* end() const { return state_.data + state_.size; }
  std::span<const T> items() const { return {state_.data, state_.size}; }
  void clear() { state_.size = 0; }
  std::size_t bytesReserved() const { return storage_.capacity() * sizeof(T); }
  State* forNativeCode() { return &state_; }

 private:
  // As a std::vector grows (the memory a robot's VM reports stays the same), out of line.
  [[gnu::noinline]] void grow(std::size_t more) {
    resize(std::max<std::size_t>(state_.size + more, storage_.size() * 2));
  }
  // Grows to n (more than the capacity): every element of the new storage is written here, so its
  // pages are prefaulted first, in one call (B2 n-queens 13: 2,700 of its 3,100 page faults).
  void resize(std::size_t n) {
    std::vector<T> grown;
    grown.reserve(n);
    support::prefault(grown.data(), n * sizeof(T));
    grown.insert(grown.end(), std::make_move_iterator(storage_.begin()),
                 std::make_move_iterator(storage_.end()));
    grown.resize(n);
    storage_.swap(grown);
    state_.data = storage_.data();
    state_.capacity = std::uint32_t(n);
  }

  std::vector<T> storage_;  // its size is the capacity
  State state_{};
};

}  // namespace meldvm
