// Facts as bytes, for the messages between simulated blocks (a fact for a neighbour travels over
// the link, and its size decides the transmission time) and between the worker threads of
// `meld -j N` (a fact leaves the sender's heap and is rebuilt in the receiver's). Layout, little-endian:
// predicate id (u16), flags (u8: 1 = retraction), then the arguments by type: int i32, float f64,
// bool u8, node/thread u32, string u32 length + bytes, list u32 count + items, struct its fields,
// array/set u32 count + items.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/predicate.hpp"

namespace meldvm {

class FactCodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Lists that share their tails keep sharing across the facts of one batch between shards. A
// program that conses (`[Y | L]` for every Y) builds many lists on one tail; sent one by one,
// each arrived with its own copy of the tail: n-queens' placements took 3.5 times the serial
// VM's heap at `meld -j 2`. With a sharing context, a list goes as the cells not yet sent in the
// batch, then a reference to the first cell already sent (or the end of the list). Cells are
// numbered in the order both sides meet them; the encoder holds a reference to each one it sent,
// so that none is freed and its address reused for another list before the batch ends.
// Block links never use it: their bytes are the format in the header comment.
class ListEncoderShare {
 public:
  explicit ListEncoderShare(Heap& heap) : heap_(&heap) {}
  ~ListEncoderShare() { reset(); }
  ListEncoderShare(ListEncoderShare&& o) noexcept;
  ListEncoderShare& operator=(ListEncoderShare&&) = delete;
  ListEncoderShare(const ListEncoderShare&) = delete;
  bool empty() const { return held_.empty(); }
  void reset();  // the batch is out: what follows shares nothing with it

 private:
  friend class ListSharingAccess;
  // Cell -> its number in the batch: open addressing, emptied in O(1) by a new generation, so a
  // batch after the first few allocates nothing.
  class CellNumbers {
   public:
    static constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;
    std::uint32_t find(const void* cell) const;
    void insert(const void* cell, std::uint32_t number);  // not present
    void clear() {
      size_ = 0;
      if (++generation_ == 0) {  // wrapped: no stale entry may look current
        entries_.assign(entries_.size(), Entry{});
        generation_ = 1;
      }
    }

   private:
    struct Entry {
      const void* cell = nullptr;
      std::uint32_t number = 0, generation = 0;
    };
    std::size_t slotOf(const void* cell) const;
    std::vector<Entry> entries_;
    std::uint32_t generation_ = 1, size_ = 0;
  };
  Heap* heap_;
  CellNumbers ids_;
  std::vector<std::pair<TypeId, Value>> held_;  // in number order
};

class ListDecoderShare {
 public:
  explicit ListDecoderShare(Heap& heap) : heap_(heap) {}
  ~ListDecoderShare() { reset(); }
  ListDecoderShare(const ListDecoderShare&) = delete;
  ListDecoderShare& operator=(const ListDecoderShare&) = delete;
  void reset();  // the batch ended

 private:
  friend class ListSharingAccess;
  Heap& heap_;
  std::vector<std::pair<TypeId, Value>> cells_;  // by number; one reference each
};

// Appends the encoding of one fact to `out` (with `share`: in the batch format above).
void encodeFact(std::vector<std::uint8_t>& out, const PredicateTable& preds, PredId p, const Value* args,
                bool negative, ListEncoderShare* share = nullptr);

struct DecodedFact {
  PredId pred = 0;
  bool negative = false;
  std::vector<Value> args;   // owned references (release them with the field types)
  std::vector<Value> stack;  // working storage of the decoder, reused
};

// Decodes one fact; throws FactCodecError on malformed input. `fact`'s vectors are reused.
// `share`: the fact was encoded with a ListEncoderShare (the same batch's earlier facts decoded
// with this one).
void decodeFact(const std::uint8_t* data, std::size_t size, const PredicateTable& preds, Heap& heap,
                DecodedFact& fact, ListDecoderShare* share = nullptr);

}  // namespace meldvm
