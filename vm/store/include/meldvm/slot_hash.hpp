// An open-addressing hash set of fact slots (linear probing, backward-shift deletion). It stores
// only (hash, slot) pairs: the key lives in the fact itself and the caller's predicate compares it.
// One table serves all nodes of a predicate (the node id is part of the key), which keeps memory
// per node small. It shrinks only when asked (shrink), so after a warm-up inserting and erasing
// allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/large_allocator.hpp"

namespace meldvm {

class SlotHash {
 public:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

  // The slot whose key matches (eq(slot) is true), or kNone.
  template <class Eq>
  std::uint32_t find(std::uint64_t hash, Eq&& eq) const {
    if (size_ == 0) return kNone;
    const std::uint32_t h = fold(hash);
    for (std::uint32_t i = h & mask_;; i = (i + 1) & mask_) {
      const Entry& e = entries_[i];
      if (e.slot == kNone) return kNone;
      if (e.hash == h && eq(e.slot)) return e.slot;
    }
  }
  [[gnu::always_inline]] void prefetch(std::uint64_t hash) const {
    if (size_ != 0) __builtin_prefetch(&entries_[fold(hash) & mask_]);
  }
  void insert(std::uint64_t hash, std::uint32_t slot);  // the key must not be present
  void reserve(std::uint32_t entries);                  // room for that many without growing
  bool erase(std::uint64_t hash, std::uint32_t slot);   // removes that exact slot
  bool replace(std::uint64_t hash, std::uint32_t oldSlot, std::uint32_t newSlot);  // same key
  // Halves the table while it stays at most a quarter full (a shard gave most of its nodes
  // away), if it is a mapping of its own (support::kMappedFrom); the bytes given back.
  std::size_t shrink();
  std::uint32_t size() const { return size_; }
  std::size_t capacity() const { return entries_.size(); }

 private:
  struct Entry {
    std::uint32_t hash;
    std::uint32_t slot;
  };
  static std::uint32_t fold(std::uint64_t h) { return std::uint32_t(h ^ (h >> 32)); }
  std::uint32_t indexOf(std::uint32_t h, std::uint32_t slot) const;
  void grow(std::size_t capacity = 0);  // 0: double

  LargeVector<Entry> entries_;
  std::uint32_t mask_ = 0;
  std::uint32_t size_ = 0;
};

}  // namespace meldvm
