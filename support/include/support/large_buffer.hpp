// A growable array of trivially copyable items on the large-page allocator (large_allocator.hpp).
//
// Why not LargeVector: std::vector with an allocator other than std::allocator relocates and
// value-initialises item by item through allocator_traits (libstdc++ keeps its memmove path for
// std::allocator), and the VM's fact slots grow by a quarter at a time: on pagerank-movies that
// copying was 3 % of all instructions. Here a large buffer grows by moving its pages (growLarge),
// a small one by one memcpy, and new items are zeroed with one memset (their pages prefaulted a
// chunk at a time, see prefault).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

#include "support/large_allocator.hpp"

namespace support {

template <class T>
class LargeBuffer {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "LargeBuffer moves its items with memcpy");

 public:
  LargeBuffer() = default;
  LargeBuffer(const LargeBuffer& o) { *this = o; }
  LargeBuffer(LargeBuffer&& o) noexcept { swap(o); }
  LargeBuffer& operator=(const LargeBuffer& o) {
    if (this != &o) {
      clear();
      reserve(o.size_);
      if (o.size_) std::memcpy(static_cast<void*>(data_), o.data_, o.size_ * sizeof(T));
      size_ = o.size_;
    }
    return *this;
  }
  LargeBuffer& operator=(LargeBuffer&& o) noexcept {
    LargeBuffer(std::move(o)).swap(*this);
    return *this;
  }
  ~LargeBuffer() {
    if (data_) freeLarge(data_, capacity_ * sizeof(T));
  }
  void swap(LargeBuffer& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

  void reserve(std::size_t n) {
    if (n <= capacity_) return;
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    data_ = static_cast<T*>(growLarge(data_, capacity_ * sizeof(T), n * sizeof(T), size_ * sizeof(T)));
    capacity_ = n;
  }
  // New items are value-initialised (all bits zero for the VM's Value and plain records); past
  // the capacity, room for max(n, twice the size), as libstdc++'s std::vector makes.
  void resize(std::size_t n) {
    if (n > capacity_) reserve(std::max(n, size_ * 2));
    if (n > size_) {
      prefaultAhead(data_, capacity_ * sizeof(T), size_ * sizeof(T), n * sizeof(T));
      std::memset(static_cast<void*>(data_ + size_), 0, (n - size_) * sizeof(T));
    }
    size_ = n;
  }
  // n more items within the capacity, not zeroed: for a caller that writes every word of them
  // (a fact table's fresh slot, where the memset was a tenth of a store on pagerank-movies).
  void extendWithin(std::size_t n) {
    prefaultAhead(data_, capacity_ * sizeof(T), size_ * sizeof(T), (size_ + n) * sizeof(T));
    size_ += n;
  }
  void clear() { size_ = 0; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
};

}  // namespace support
