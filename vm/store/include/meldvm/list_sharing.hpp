// Lists that keep sharing their tails across the facts of one batch between shards (the worker
// threads of `meld -j N`, the simulated chip's cores). A program that conses (`[Y | L]` for
// every Y) builds many lists on one tail; sent one by one, each arrived with its own copy of the
// tail: n-queens' placements took 3.5 times the serial VM's heap at `meld -j 2`. With these, a
// list goes as the cells not yet sent in the batch and a reference to the first one already sent
// (fact_codec.hpp has the bytes). Cells are numbered in the order both sides meet them; the
// encoder holds a reference to each cell it sent, so that none is freed and its address reused
// for another list before the batch ends. Block links never use them.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/slot_hash.hpp"

namespace meldvm {

// The sender's side: one per batch being filled (per destination), on the sender's heap.
class ListEncoderShare {
 public:
  static constexpr std::uint32_t kNotSent = SlotHash::kNone;

  explicit ListEncoderShare(Heap& heap) : heap_(&heap) {}
  ~ListEncoderShare() { reset(); }
  ListEncoderShare(ListEncoderShare&& o) noexcept;
  ListEncoderShare& operator=(ListEncoderShare&&) = delete;
  ListEncoderShare(const ListEncoderShare&) = delete;

  // The number of list cell `cell` in this batch, or kNotSent.
  std::uint32_t numberOf(const void* cell) const {
    return numbers_.find(hashOf(cell), [&](std::uint32_t n) { return held_[n].second.asObject() == cell; });
  }
  // `cell` (a list of type listType) went out: it gets the next number and is held until reset().
  void sent(TypeId listType, Value cell);
  bool empty() const { return held_.empty(); }
  void reset();  // the batch is out: what follows shares nothing with it

 private:
  static std::uint64_t hashOf(const void* cell) {
    return std::uint64_t(reinterpret_cast<std::uintptr_t>(cell)) * 0x9E3779B97F4A7C15ull;
  }

  Heap* heap_;
  SlotHash numbers_;                            // a cell's address -> its number (its index in held_)
  std::vector<std::pair<TypeId, Value>> held_;  // in number order
};

// The receiver's side: one per batch being taken in, on the receiver's heap.
class ListDecoderShare {
 public:
  explicit ListDecoderShare(Heap& heap) : heap_(heap) {}
  ~ListDecoderShare() { reset(); }
  ListDecoderShare(const ListDecoderShare&) = delete;
  ListDecoderShare& operator=(const ListDecoderShare&) = delete;

  std::size_t cells() const { return cells_.size(); }
  Value cell(std::uint32_t number) const { return cells_[number].second; }  // number < cells()
  // The first `count` cells of `list` (of type listType) were just built: they get the next
  // numbers and are held until reset().
  void built(TypeId listType, Value list, std::uint32_t count);
  void reset();  // the batch ended

 private:
  Heap& heap_;
  std::vector<std::pair<TypeId, Value>> cells_;  // by number; one reference each
};

}  // namespace meldvm
