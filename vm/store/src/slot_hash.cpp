#include "meldvm/slot_hash.hpp"

#include <algorithm>
#include <stdexcept>

namespace meldvm {

void SlotHash::reserve(std::uint32_t entries) {
  std::size_t cap = entries_ ? capacity() : 16;
  while (overloaded(entries, cap)) cap *= 2;
  if (cap > capacity()) grow(cap);
}

void SlotHash::grow(std::size_t cap) {
  Entry* const old = entries_;
  const std::size_t oldCapacity = capacity();
  if (cap == 0) cap = old ? oldCapacity * 2 : 16;
  if (cap - 1 > 0xFFFFFFFFu) throw std::length_error("meldvm: hash table too large");
  entries_ = LargeAllocator<Entry>().allocate(cap);
  support::prefault(entries_, cap * sizeof(Entry));  // all written at once
  std::fill(entries_, entries_ + cap, Entry{0, kNone});
  mask_ = std::uint32_t(cap - 1);
  for (std::size_t k = 0; k < oldCapacity; ++k) {
    const Entry& e = old[k];
    if (e.slot == kNone) continue;
    std::uint32_t i = e.hash & mask_;
    while (entries_[i].slot != kNone) i = (i + 1) & mask_;
    entries_[i] = e;
  }
  if (old) LargeAllocator<Entry>().deallocate(old, oldCapacity);
}

std::size_t SlotHash::shrink() {
  // A table below kMappedFrom came from operator new: its memory would stay with the process.
  if (capacity() * sizeof(Entry) < support::kMappedFrom) return 0;
  std::size_t cap = capacity();
  while (cap / 2 >= 16 && std::size_t(size_) * 4 <= cap / 2) cap /= 2;
  if (cap == capacity()) return 0;
  const std::size_t before = capacity();
  grow(cap);
  return (before - cap) * sizeof(Entry);
}

void SlotHash::insert(std::uint64_t hash, std::uint32_t slot) {
  if (!entries_ || overloaded(size_ + 1, capacity())) grow();
  const std::uint32_t h = fold(hash);
  std::uint32_t i = h & mask_;
  while (entries_[i].slot != kNone) i = (i + 1) & mask_;
  entries_[i] = Entry{h, slot};
  ++size_;
}

std::uint32_t SlotHash::indexOf(std::uint32_t h, std::uint32_t slot) const {
  if (size_ == 0) return kNone;
  for (std::uint32_t i = h & mask_;; i = (i + 1) & mask_) {
    const Entry& e = entries_[i];
    if (e.slot == kNone) return kNone;
    if (e.slot == slot) return i;
  }
}

bool SlotHash::replace(std::uint64_t hash, std::uint32_t oldSlot, std::uint32_t newSlot) {
  const std::uint32_t i = indexOf(fold(hash), oldSlot);
  if (i == kNone) return false;
  entries_[i].slot = newSlot;
  return true;
}

bool SlotHash::erase(std::uint64_t hash, std::uint32_t slot) {
  std::uint32_t i = indexOf(fold(hash), slot);
  if (i == kNone) return false;
  // Backward shift: pull later entries of the probe run into the hole when their home position
  // does not lie cyclically in (hole, their position].
  for (std::uint32_t j = (i + 1) & mask_; entries_[j].slot != kNone; j = (j + 1) & mask_) {
    const std::uint32_t home = entries_[j].hash & mask_;
    const bool stays = i <= j ? (i < home && home <= j) : (i < home || home <= j);
    if (!stays) {
      entries_[i] = entries_[j];
      i = j;
    }
  }
  entries_[i] = Entry{0, kNone};
  --size_;
  return true;
}

}  // namespace meldvm
