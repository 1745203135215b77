// Free-list slot pools: slots are reused, so the steady state allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

namespace simcore {

inline constexpr std::uint32_t kNoSlot = 0xFFFFFFFFu;

// Growing is rare and long; kept apart so that the reuse path inlines into the hot callers (GCC
// stopped inlining the whole when move() grew).
template <class Pool>
[[gnu::noinline]] std::uint32_t growPool(Pool& pool) {
  pool.emplace_back();
  return std::uint32_t(pool.size() - 1);
}

template <class Pool>
[[gnu::always_inline]] inline std::uint32_t allocateSlot(Pool& pool, std::uint32_t& freeList) {
  if (freeList != kNoSlot) [[likely]] {
    const std::uint32_t i = freeList;
    freeList = pool[i].nextFree;
    return i;
  }
  return growPool(pool);
}

template <class Pool>
[[gnu::always_inline]] inline void releaseSlot(Pool& pool, std::uint32_t& freeList, std::uint32_t i) {
  pool[i].nextFree = freeList;
  freeList = i;
}

}  // namespace simcore
