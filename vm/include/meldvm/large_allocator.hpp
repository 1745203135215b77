// An allocator for the VM's big arrays (fact slots, hash tables, mailbox slabs, per-node
// records): blocks of 2 MiB and more are aligned to 2 MiB and marked for transparent huge pages.
//
// Why: a large run touches these arrays at random (a message goes to any node), so with 4 KiB
// pages nearly every access also misses the TLB. Where the kernel gives huge pages only on request
// (transparent_hugepage=madvise, the Debian default), asking for them made the B2 shortest-path run
// about 6% faster. Elsewhere the hint is ignored. Small blocks use operator new as usual.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace meldvm {

namespace detail {
inline constexpr std::size_t kHugePage = std::size_t(2) << 20;
void* allocateLarge(std::size_t bytes);  // bytes >= kHugePage
void freeLarge(void* p);
}  // namespace detail

template <class T>
struct LargeAllocator {
  using value_type = T;
  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < detail::kHugePage) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(detail::allocateLarge(bytes));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < detail::kHugePage)
      ::operator delete(p);
    else
      detail::freeLarge(p);
  }
  template <class U>
  bool operator==(const LargeAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

}  // namespace meldvm
