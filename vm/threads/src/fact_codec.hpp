// Facts in transit between threads, as words: a fact leaves the sender's heap and arrives in the
// receiver's, so its boxed values (strings, lists, structs, arrays, sets) are copied in full.
// Scalars take one word; a string its length and its bytes; a list, array, set or struct its item
// count and its items. The encoding needs no allocation beyond the growth of the word buffer,
// whose capacity is kept from batch to batch.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/predicate.hpp"

namespace meldvm::threads {

using Words = std::vector<std::uint64_t>;

// Appends the arguments (home excluded) of a fact of p.
void encodeArgs(Words& out, const PredicateDesc& p, const TypeTable& types, const Value* args);

// Reads the arguments of a fact of p at words[pos...] into `args` (p.arity() values), building
// the boxed ones in `heap` (the caller owns those references); returns the position after them.
// `scratch` is working room kept by the caller. The words come from encodeArgs in the same
// process: a damaged buffer is a bug, not input.
std::size_t decodeArgs(const Words& words, std::size_t pos, const PredicateDesc& p, Heap& heap, Value* args,
                       std::vector<Value>& scratch);

// Releases what decodeArgs built.
void releaseArgs(const PredicateDesc& p, Heap& heap, const Value* args);

}  // namespace meldvm::threads
