// A Meld value in 8 bytes, untagged. The type of a value is always known from its context (the
// field types of a predicate, the type of a register), as in the established VM, so a stored fact
// is just `arity` words: no tag bytes, no padding. Scalars live in the word itself; strings, lists,
// structs, arrays and sets are pointers to reference-counted objects of a Heap (heap.hpp).
#pragma once

#include <bit>
#include <cstdint>

namespace meldvm {

using NodeId = std::uint32_t;
using ThreadId = std::uint32_t;

struct Object;  // heap.hpp

class Value {
 public:
  constexpr Value() = default;

  // Every constructor writes a canonical bit pattern (ints sign-extended, bools 0/1, ids
  // zero-extended), so scalar equality other than float equality is equality of bits.
  static constexpr Value fromInt(std::int32_t i) { return Value(std::uint64_t(std::int64_t(i))); }
  static constexpr Value fromFloat(double d) { return Value(std::bit_cast<std::uint64_t>(d)); }
  static constexpr Value fromBool(bool b) { return Value(b ? 1u : 0u); }
  static constexpr Value fromNode(NodeId n) { return Value(n); }
  static constexpr Value fromThread(ThreadId t) { return Value(t); }
  static Value fromObject(const Object* o) {
    return Value(std::uint64_t(reinterpret_cast<std::uintptr_t>(o)));
  }
  static constexpr Value nil() { return Value(0); }  // the empty list
  static constexpr Value fromBits(std::uint64_t b) { return Value(b); }

  constexpr std::int32_t asInt() const { return std::int32_t(std::uint32_t(bits_)); }
  constexpr double asFloat() const { return std::bit_cast<double>(bits_); }
  constexpr bool asBool() const { return bits_ != 0; }
  constexpr NodeId asNode() const { return NodeId(bits_); }
  constexpr ThreadId asThread() const { return ThreadId(bits_); }
  Object* asObject() const { return reinterpret_cast<Object*>(std::uintptr_t(bits_)); }
  constexpr bool isNil() const { return bits_ == 0; }
  constexpr std::uint64_t bits() const { return bits_; }

 private:
  constexpr explicit Value(std::uint64_t b) : bits_(b) {}
  std::uint64_t bits_ = 0;
};
static_assert(sizeof(Value) == 8);

}  // namespace meldvm
