// Operations on typed values: equality and hashing (fact identity in the store), a total order
// (aggregates, sorting built-ins) and the text form of the database dump (spec §8).
#pragma once

#include <cstdint>
#include <string>

#include "meldvm/types.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

// Structural equality. Floats compare as numbers (0.0 == -0.0), except that a NaN equals a NaN with
// the same bits, so that a fact holding a NaN is still one fact in a persistent store.
bool valuesEqual(const TypeTable& types, TypeId t, Value a, Value b);

// Consistent with valuesEqual.
std::uint64_t hashValue(const TypeTable& types, TypeId t, Value v);

// Negative, zero or positive. Numbers by value (NaN after everything), bool false < true, nodes and
// threads by id, strings byte-wise, lists/structs/arrays/sets lexicographically by item.
int compareValues(const TypeTable& types, TypeId t, Value a, Value b);

// The same three, inlined for the integer-like kinds (int, bool, node, thread) that fill most
// facts: the store's hot paths call these.
inline bool integerLike(const TypeTable& types, TypeId t) {
  const TypeKind k = types.kind(t);
  return k == TypeKind::Int || k == TypeKind::Bool || k == TypeKind::Node || k == TypeKind::Thread;
}
inline bool valuesEqualFast(const TypeTable& types, TypeId t, Value a, Value b) {
  return integerLike(types, t) ? a.bits() == b.bits() : valuesEqual(types, t, a, b);
}

// Appends the dump form of a value (§8): int decimal, float as printf("%.5g"), true/false, @N, #TN,
// "raw string", [a,b] (no spaces, every element), :(a, b), #[a, b], {a, b}.
void appendValue(std::string& out, const TypeTable& types, TypeId t, Value v);
void appendFloat(std::string& out, double d);

// 64-bit mixing step shared by the store's hash tables.
inline std::uint64_t mixHash(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  h ^= h >> 31;
  h *= 0xbf58476d1ce4e5b9ull;
  return h ^ (h >> 29);
}

// What hashValue gives an int, bool, node or thread (their bits are their identity).
inline std::uint64_t hashIntegerLike(Value v) { return mixHash(2, v.bits()); }
inline std::uint64_t hashValueFast(const TypeTable& types, TypeId t, Value v) {
  return integerLike(types, t) ? hashIntegerLike(v) : hashValue(types, t, v);
}
inline int compareValuesFast(const TypeTable& types, TypeId t, Value a, Value b) {
  if (types.kind(t) == TypeKind::Int) return (a.asInt() > b.asInt()) - (a.asInt() < b.asInt());
  return compareValues(types, t, a, b);
}

}  // namespace meldvm
