// Free-list slot pools: slots are reused, so the steady state allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

namespace simcore {

inline constexpr std::uint32_t kNoSlot = 0xFFFFFFFFu;

template <class Pool>
std::uint32_t allocateSlot(Pool& pool, std::uint32_t& freeList) {
  if (freeList != kNoSlot) {
    const std::uint32_t i = freeList;
    freeList = pool[i].nextFree;
    return i;
  }
  pool.emplace_back();
  return std::uint32_t(pool.size() - 1);
}

template <class Pool>
void releaseSlot(Pool& pool, std::uint32_t& freeList, std::uint32_t i) {
  pool[i].nextFree = freeList;
  freeList = i;
}

}  // namespace simcore
