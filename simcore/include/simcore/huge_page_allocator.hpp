// An allocator for the kernel's big arrays (blocks, grid, faces, event buckets). A million blocks
// are visited in random order, so with 4 KiB pages nearly every visit also misses the TLB; arrays of
// 2 MiB and more are aligned to 2 MiB and advised to use transparent huge pages where the OS allows
// (Linux "madvise" mode). Smaller arrays use plain operator new.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace simcore {

inline constexpr std::size_t kHugePageSize = std::size_t(2) << 20;

inline void* allocateLarge(std::size_t bytes) {
  if (bytes < kHugePageSize) return ::operator new(bytes);
  const std::size_t rounded = (bytes + kHugePageSize - 1) & ~(kHugePageSize - 1);
  void* p = std::aligned_alloc(kHugePageSize, rounded);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure changes speed, not behaviour
#endif
  return p;
}

inline void deallocateLarge(void* p, std::size_t bytes) {
  if (bytes < kHugePageSize)
    ::operator delete(p);
  else
    std::free(p);
}

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocateLarge(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) { deallocateLarge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const {
    return true;
  }
};

}  // namespace simcore
