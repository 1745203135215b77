// An allocator for the big arrays of the kernel (blocks, grid, faces, event buckets) and of the VM
// (fact slots, hash tables, mailbox slabs, per-node records): blocks of 128 KiB and more are
// mappings of their own, those of 2 MiB and more aligned to 2 MiB and marked for transparent huge
// pages (a block that growLarge moved may lose the alignment); smaller ones use operator new.
//
// Why huge pages: a large run touches these arrays at random (a message goes to any block or
// node), so with 4 KiB pages nearly every access also misses the TLB. Where the kernel gives huge
// pages only on request (transparent_hugepage=madvise, the Debian default), asking for them made
// the B2 shortest-path run about 6% faster. Elsewhere the hint is ignored.
//
// Why mappings from 128 KiB: growLarge then moves the pages of a growing block instead of copying
// them into fresh ones. The VM's fact slots grow by a quarter at a time; copied, they faulted in
// about four times their final size (on pagerank-movies, 28 % of the run's page faults).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace support {

inline constexpr std::size_t kHugePage = std::size_t(2) << 20;

inline constexpr std::size_t kMappedFrom = std::size_t(128) << 10;

inline std::size_t hugePages(std::size_t bytes) { return (bytes + kHugePage - 1) & ~(kHugePage - 1); }

// The length of the mapping of a block of `bytes` (the kernel rounds the smaller ones to pages).
inline std::size_t mappedBytes(std::size_t bytes) { return bytes >= kHugePage ? hugePages(bytes) : bytes; }

inline void* allocateLarge(std::size_t bytes);
inline void freeLarge(void* p, std::size_t bytes) noexcept;

// Ranges from this size are worth prefaulting (prefault); below, one system call saves too few
// faults to pay for itself.
inline constexpr std::size_t kPrefaultFrom = std::size_t(16) << 10;

// Maps in the pages that lie wholly inside [p, p + bytes) for writing, as writing them would, but
// in one system call (MADV_POPULATE_WRITE, Linux 5.14; elsewhere, or on failure, nothing happens:
// the pages fault in when written). The contents do not change.
//
// Why: on the project's VMs a page's first write faults for 5 to 15 us, and a batch costs about
// half of that a page. The VM's fact slots, hash tables, list heads, mail slabs and buffers are
// written soon after they grow; prefaulted, pagerank-movies faults 460 times instead of 2,040 and
// B2 shortest-path 3,600 instead of 21,600. Callers prefault only what they write at once or
// next (prefaultAhead: a chunk ahead), so memory use stays what it was.
inline void prefault(void* p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  constexpr std::uintptr_t kPage = 4096;  // where pages are larger, madvise refuses: no harm
  if (bytes < kPrefaultFrom) return;
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) & ~(kPage - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kPage - 1);
  if (end > first) (void)madvise(reinterpret_cast<void*>(first), end - first, MADV_POPULATE_WRITE);
#else
  (void)p, (void)bytes;
#endif
}

// For a block of allocateLarge(blockBytes) that is written front to back: the bytes [from, to) are
// about to be written, those below `from` have been. A mapped block is prefaulted a chunk of
// kPrefaultChunk at a time, as the writes first reach each chunk (at most a chunk ahead of them).
inline constexpr std::size_t kPrefaultChunk = std::size_t(64) << 10;
inline void prefaultAhead(void* block, std::size_t blockBytes, std::size_t from, std::size_t to) noexcept {
  if (blockBytes < kMappedFrom) return;
  const std::size_t untouched = (from + kPrefaultChunk - 1) & ~(kPrefaultChunk - 1);
  if (to <= untouched) return;
  const std::size_t end = std::min(blockBytes, (to + kPrefaultChunk - 1) & ~(kPrefaultChunk - 1));
  prefault(static_cast<char*>(block) + untouched, end - untouched);
}

// growLarge's way where pages cannot move: a new block, the used bytes copied, the old one freed.
inline void* copyToLarger(void* p, std::size_t oldBytes, std::size_t newBytes, std::size_t usedBytes) {
  void* q = allocateLarge(newBytes);
  prefault(q, usedBytes);  // the copy writes them at once
  if (usedBytes) std::memcpy(q, p, usedBytes);
  if (p) freeLarge(p, oldBytes);
  return q;
}

#if defined(__linux__)
// Large blocks are mappings of their own (from 2 MiB, 2 MiB-aligned: the unaligned ends of a
// larger mapping are given back), so that growLarge can move their pages instead of copying them.
inline void* allocateLarge(std::size_t bytes) {
  if (bytes < kMappedFrom) return ::operator new(bytes);
  if (bytes < kHugePage) {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return p;
  }
  const std::size_t rounded = hugePages(bytes);
  void* raw = mmap(nullptr, rounded + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  char* start = static_cast<char*>(raw);
  char* aligned =
      reinterpret_cast<char*>((reinterpret_cast<std::uintptr_t>(start) + kHugePage - 1) & ~(kHugePage - 1));
  if (aligned != start) munmap(start, std::size_t(aligned - start));
  if (char* end = aligned + rounded; end != start + rounded + kHugePage)
    munmap(end, std::size_t(start + rounded + kHugePage - end));
#if defined(MADV_HUGEPAGE)
  (void)madvise(aligned, rounded, MADV_HUGEPAGE);  // a hint: failure only means small pages
#endif
  return aligned;
}

// Gives back the memory of whole pages inside a block of allocateLarge(blockBytes) (offset and
// length page-aligned): they read as zeros afterwards and take memory again when written. Blocks
// below kMappedFrom (operator new) keep theirs; returns whether the pages were given back.
inline bool discardPages(void* block, std::size_t blockBytes, std::size_t offset,
                         std::size_t length) noexcept {
  if (blockBytes < kMappedFrom) return false;
  return madvise(static_cast<char*>(block) + offset, length, MADV_DONTNEED) == 0;
}

inline void freeLarge(void* p, std::size_t bytes) noexcept {
  if (bytes < kMappedFrom)
    ::operator delete(p);
  else
    munmap(p, mappedBytes(bytes));
}

// A block of allocateLarge(oldBytes) as one of newBytes (more), its first usedBytes kept. Between
// mapped blocks the kernel moves the pages (mremap): no copying, however often a table grows.
inline void* growLarge(void* p, std::size_t oldBytes, std::size_t newBytes, std::size_t usedBytes) {
  if (oldBytes >= kMappedFrom) {
    void* q = mremap(p, mappedBytes(oldBytes), mappedBytes(newBytes), MREMAP_MAYMOVE);
    if (q == MAP_FAILED) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
    if (newBytes >= kHugePage) (void)madvise(q, mappedBytes(newBytes), MADV_HUGEPAGE);
#endif
    return q;
  }
  return copyToLarger(p, oldBytes, newBytes, usedBytes);
}
#else
inline void* allocateLarge(std::size_t bytes) { return ::operator new(bytes); }
inline void freeLarge(void* p, std::size_t) noexcept { ::operator delete(p); }
inline bool discardPages(void*, std::size_t, std::size_t, std::size_t) noexcept { return false; }
inline void* growLarge(void* p, std::size_t oldBytes, std::size_t newBytes, std::size_t usedBytes) {
  return copyToLarger(p, oldBytes, newBytes, usedBytes);
}
#endif

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
