// The Meld type language of the runtime (spec §3.1): int (32-bit), float (double), bool, node,
// thread, string, list T, struct :(T1, ...), array T, set T. Node subtypes and aliases are compile-
// time notions and reach the VM as plain `node` / the aliased type. Types are interned in a table,
// so a TypeId comparison is a type comparison and a value needs no type tag of its own.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace meldvm {

enum class TypeKind : std::uint8_t { Int, Float, Bool, Node, Thread, String, List, Struct, Array, Set };

using TypeId = std::uint32_t;

class TypeTable {
 public:
  // The scalar types and string are always present with these ids.
  static constexpr TypeId kInt = 0, kFloat = 1, kBool = 2, kNode = 3, kThread = 4, kString = 5;

  TypeTable();

  TypeId list(TypeId element);
  TypeId array(TypeId element);
  TypeId set(TypeId element);
  TypeId structOf(std::span<const TypeId> fields);

  TypeKind kind(TypeId t) const { return entries_[t].kind; }
  TypeId element(TypeId t) const { return entries_[t].element; }  // list/array/set only
  std::span<const TypeId> fields(TypeId t) const {                // struct only
    return {fieldPool_.data() + entries_[t].firstField, entries_[t].fieldCount};
  }
  // A boxed value is a pointer to a reference-counted heap object (or nil for the empty list).
  bool boxed(TypeId t) const { return entries_[t].kind >= TypeKind::String; }
  std::size_t size() const { return entries_.size(); }
  std::string name(TypeId t) const;  // "list int", ":(int, float)", for messages

 private:
  struct Entry {
    TypeKind kind;
    TypeId element;
    std::uint32_t firstField, fieldCount;
  };
  TypeId intern(TypeKind kind, TypeId element, std::span<const TypeId> fields);
  void check(TypeId t) const;

  std::vector<Entry> entries_;
  std::vector<TypeId> fieldPool_;
};

}  // namespace meldvm
