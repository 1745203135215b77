// Facts as bytes, for the messages between simulated blocks (a fact for a neighbour travels over
// the link, and its size decides the transmission time). (The worker threads of `meld -j N` hand
// values over instead: meldvm/shard_mail.hpp.) Layout, little-endian:
// predicate id (u16), flags (u8: 1 = retraction), then the arguments by type: int i32, float f64,
// bool u8, node/thread u32, string u32 length + bytes, list u32 count + items, struct its fields,
// array/set u32 count + items.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/predicate.hpp"

namespace meldvm {

class FactCodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Appends the encoding of one fact to `out`.
void encodeFact(std::vector<std::uint8_t>& out, const PredicateTable& preds, PredId p, const Value* args,
                bool negative);

struct DecodedFact {
  PredId pred = 0;
  bool negative = false;
  std::vector<Value> args;   // owned references (release them with the field types)
  std::vector<Value> stack;  // working storage of the decoder, reused
};

// Decodes one fact; throws FactCodecError on malformed input. `fact`'s vectors are reused.
void decodeFact(const std::uint8_t* data, std::size_t size, const PredicateTable& preds, Heap& heap,
                DecodedFact& fact);

}  // namespace meldvm
