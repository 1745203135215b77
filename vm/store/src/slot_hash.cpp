#include "meldvm/slot_hash.hpp"

namespace meldvm {

namespace {
// At most half full: linear probing with deletions slows down quickly above that (measured: a
// load of 0.7 made the B2 shortest-path run 2.5 times slower).
bool overloaded(std::size_t entries, std::size_t capacity) { return entries * 2 > capacity; }
}  // namespace

void SlotHash::reserve(std::uint32_t entries) {
  std::size_t cap = entries_.empty() ? 16 : entries_.size();
  while (overloaded(entries, cap)) cap *= 2;
  if (cap > entries_.size()) grow(cap);
}

void SlotHash::grow(std::size_t capacity) {
  LargeVector<Entry> old = std::move(entries_);
  entries_.assign(capacity ? capacity : old.empty() ? 16 : old.size() * 2, Entry{0, kNone});
  mask_ = std::uint32_t(entries_.size() - 1);
  for (const Entry& e : old) {
    if (e.slot == kNone) continue;
    std::uint32_t i = e.hash & mask_;
    while (entries_[i].slot != kNone) i = (i + 1) & mask_;
    entries_[i] = e;
  }
}

std::size_t SlotHash::shrink() {
  // A table below kMappedFrom came from operator new: its memory would stay with the process.
  if (entries_.size() * sizeof(Entry) < support::kMappedFrom) return 0;
  std::size_t cap = entries_.size();
  while (cap / 2 >= 16 && std::size_t(size_) * 4 <= cap / 2) cap /= 2;
  if (cap == entries_.size()) return 0;
  const std::size_t before = entries_.size();
  grow(cap);
  return (before - cap) * sizeof(Entry);
}

void SlotHash::insert(std::uint64_t hash, std::uint32_t slot) {
  if (entries_.empty() || overloaded(size_ + 1, entries_.size())) grow();
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
