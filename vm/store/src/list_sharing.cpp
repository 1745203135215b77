#include "meldvm/list_sharing.hpp"

#include <algorithm>

#include "meldvm/value_ops.hpp"

namespace meldvm {

ListEncoderShare::ListEncoderShare(ListEncoderShare&& o) noexcept
    : heap_(o.heap_), numbers_(std::move(o.numbers_)), held_(std::move(o.held_)) {
  o.numbers_.clear();
  o.held_.clear();
}

void ListEncoderShare::sent(TypeId listType, Value cell) {
  numbers_.insert(cell.asObject(), std::uint32_t(held_.size()));
  heap_->retain(listType, cell);
  held_.emplace_back(listType, cell);
}

void ListEncoderShare::reset() {
  for (const auto& [t, v] : held_) heap_->release(t, v);
  held_.clear();
  numbers_.clear();
}

std::size_t ListEncoderShare::CellNumbers::slotOf(const void* cell) const {
  const auto h = std::uint64_t(reinterpret_cast<std::uintptr_t>(cell)) * 0x9E3779B97F4A7C15ull;
  return std::size_t(h >> 32) & (entries_.size() - 1);
}

std::uint32_t ListEncoderShare::CellNumbers::find(const void* cell) const {
  if (size_ == 0) return kNotSent;
  for (std::size_t i = slotOf(cell);; i = (i + 1) & (entries_.size() - 1)) {
    const Entry& e = entries_[i];
    if (e.generation != generation_) return kNotSent;
    if (e.cell == cell) return e.number;
  }
}

void ListEncoderShare::CellNumbers::insert(const void* cell, std::uint32_t number) {
  if (2 * (std::size_t(size_) + 1) > entries_.size()) {  // at most half full: short probes
    std::vector<Entry> old(std::max<std::size_t>(64, 2 * entries_.size()));
    old.swap(entries_);
    const std::uint32_t live = generation_;
    size_ = 0;
    for (const Entry& e : old)
      if (e.generation == live) insert(e.cell, e.number);
  }
  std::size_t i = slotOf(cell);
  while (entries_[i].generation == generation_) i = (i + 1) & (entries_.size() - 1);
  entries_[i] = {cell, number, generation_};
  ++size_;
}

void ListEncoderShare::CellNumbers::clear() {
  size_ = 0;
  if (++generation_ == 0) {  // wrapped: no stale entry may look current
    entries_.assign(entries_.size(), Entry{});
    generation_ = 1;
  }
}

void ListDecoderShare::built(TypeId listType, Value list, std::uint32_t count) {
  for (std::uint32_t i = 0; i < count; ++i, list = listTail(list)) {
    heap_.retain(listType, list);
    cells_.emplace_back(listType, list);
  }
}

void ListDecoderShare::reset() {
  for (const auto& [t, v] : cells_) heap_.release(t, v);
  cells_.clear();
}

}  // namespace meldvm
