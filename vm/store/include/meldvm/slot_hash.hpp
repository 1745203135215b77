// An open-addressing hash set of fact slots (linear probing, backward-shift deletion). It stores
// only (hash, slot) pairs: the key lives in the fact itself and the caller's predicate compares it.
// One table serves all nodes of a predicate (the node id is part of the key), which keeps memory
// per node small. It shrinks only when asked (shrink), so after a warm-up inserting and erasing
// allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "meldvm/key_hash.hpp"
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
  // The slot whose key matches, or kNone after `slot` was added under this hash: one probe where
  // find and then insert took two (every fact stored into an index with a new key).
  template <class Eq>
  std::uint32_t findOrInsert(std::uint64_t hash, Eq&& eq, std::uint32_t slot) {
    if (!entries_ || overloaded(size_ + 1, capacity())) [[unlikely]]
      grow();  // (perhaps one entry early, when the key is there)
    const std::uint32_t h = fold(hash);
    for (std::uint32_t i = h & mask_;; i = (i + 1) & mask_) {
      Entry& e = entries_[i];
      if (e.slot == kNone) {
        e = Entry{h, slot};
        ++size_;
        return kNone;
      }
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
  std::size_t capacity() const { return entries_ ? std::size_t(mask_) + 1 : 0; }
  // Native code looks keys up itself (native_abi.h's meld_native_field_index): where the entries
  // are (this address does not move; the entries do when the table grows), each one 8-byte word
  // with the folded hash in its low half and the slot in its high half, and the mask and count.
  const std::uint64_t* const* entriesAddress() const {
    static_assert(sizeof(Entry) == 8 && offsetof(Entry, hash) == 0 && offsetof(Entry, slot) == 4);
    return reinterpret_cast<const std::uint64_t* const*>(&entries_);
  }
  const std::uint32_t* maskAddress() const { return &mask_; }
  const std::uint32_t* sizeAddress() const { return &size_; }

  SlotHash() = default;
  ~SlotHash() { release(); }
  SlotHash(SlotHash&& o) noexcept : entries_(o.entries_), mask_(o.mask_), size_(o.size_) { o.forget(); }
  SlotHash& operator=(SlotHash&& o) noexcept {
    if (this != &o) {
      release();
      entries_ = o.entries_, mask_ = o.mask_, size_ = o.size_;
      o.forget();
    }
    return *this;
  }
  SlotHash(const SlotHash&) = delete;
  SlotHash& operator=(const SlotHash&) = delete;

 private:
  struct Entry {
    std::uint32_t hash;
    std::uint32_t slot;
  };
  static std::uint32_t fold(std::uint64_t h) { return key_hash::fold(h); }
  // At most half full: linear probing with deletions slows down quickly above that (measured: a
  // load of 0.7 made the B2 shortest-path run 2.5 times slower).
  static bool overloaded(std::size_t entries, std::size_t capacity) { return entries * 2 > capacity; }
  std::uint32_t indexOf(std::uint32_t h, std::uint32_t slot) const;
  void grow(std::size_t capacity = 0);  // 0: double

  void release() noexcept {
    if (entries_) LargeAllocator<Entry>().deallocate(entries_, capacity());
  }
  void forget() noexcept { entries_ = nullptr, mask_ = 0, size_ = 0; }

  // capacity() entries, a power of two, or none (nullptr) before the first insertion. (A pointer
  // and the mask, not a vector: the pointer's address is what native code reads, and a
  // FactTable, which holds one SlotHash, stays 256 bytes.)
  Entry* entries_ = nullptr;
  std::uint32_t mask_ = 0;
  std::uint32_t size_ = 0;
};

}  // namespace meldvm
