// An allocator for the big arrays of the kernel (blocks, grid, faces, event buckets) and of the VM
// (fact slots, hash tables, mailbox slabs, per-node records): blocks of 2 MiB and more are aligned
// to 2 MiB and marked for transparent huge pages; smaller ones use operator new.
//
// Why: a large run touches these arrays at random (a message goes to any block or node), so with
// 4 KiB pages nearly every access also misses the TLB. Where the kernel gives huge pages only on
// request (transparent_hugepage=madvise, the Debian default), asking for them made the B2
// shortest-path run about 6% faster. Elsewhere the hint is ignored.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace support {

inline constexpr std::size_t kHugePage = std::size_t(2) << 20;

inline void* allocateLarge(std::size_t bytes) {
  if (bytes < kHugePage) return ::operator new(bytes);
  const std::size_t rounded = (bytes + kHugePage - 1) & ~(kHugePage - 1);
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure only means small pages
#endif
  return p;
}

inline void freeLarge(void* p, std::size_t bytes) noexcept {
  if (bytes < kHugePage)
    ::operator delete(p);
  else
    std::free(p);
}

template <class T>
struct LargeAllocator {
  using value_type = T;
  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocateLarge(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { freeLarge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const LargeAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

}  // namespace support
