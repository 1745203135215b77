#include "meldvm/types.hpp"

#include <algorithm>
#include <stdexcept>

namespace meldvm {

TypeTable::TypeTable() {
  // Order fixes the kXxx constants of the header.
  for (TypeKind k :
       {TypeKind::Int, TypeKind::Float, TypeKind::Bool, TypeKind::Node, TypeKind::Thread, TypeKind::String})
    entries_.push_back(Entry{k, 0, 0, 0});
}

void TypeTable::check(TypeId t) const {
  if (t >= entries_.size()) throw std::out_of_range("meldvm: unknown type id " + std::to_string(t));
}

// A handful of types per program: a linear search keeps interning simple and allocation-free on hits.
TypeId TypeTable::intern(TypeKind kind, TypeId element, std::span<const TypeId> fieldTypes) {
  for (TypeId t = 0; t < entries_.size(); ++t) {
    const Entry& e = entries_[t];
    if (e.kind == kind && e.element == element && e.fieldCount == fieldTypes.size() &&
        std::equal(fieldTypes.begin(), fieldTypes.end(), fieldPool_.begin() + e.firstField))
      return t;
  }
  const auto first = std::uint32_t(fieldPool_.size());
  fieldPool_.insert(fieldPool_.end(), fieldTypes.begin(), fieldTypes.end());
  entries_.push_back(Entry{kind, element, first, std::uint32_t(fieldTypes.size())});
  return TypeId(entries_.size() - 1);
}

TypeId TypeTable::list(TypeId element) {
  check(element);
  return intern(TypeKind::List, element, {});
}
TypeId TypeTable::array(TypeId element) {
  check(element);
  return intern(TypeKind::Array, element, {});
}
TypeId TypeTable::set(TypeId element) {
  check(element);
  return intern(TypeKind::Set, element, {});
}
TypeId TypeTable::structOf(std::span<const TypeId> fieldTypes) {
  for (TypeId f : fieldTypes) check(f);
  return intern(TypeKind::Struct, 0, fieldTypes);
}

std::string TypeTable::name(TypeId t) const {
  check(t);
  switch (kind(t)) {
    case TypeKind::Int:
      return "int";
    case TypeKind::Float:
      return "float";
    case TypeKind::Bool:
      return "bool";
    case TypeKind::Node:
      return "node";
    case TypeKind::Thread:
      return "thread";
    case TypeKind::String:
      return "string";
    case TypeKind::List:
      return "list " + name(element(t));
    case TypeKind::Array:
      return "array " + name(element(t));
    case TypeKind::Set:
      return "set " + name(element(t));
    case TypeKind::Struct: {
      std::string s = ":(";
      bool firstField = true;
      for (TypeId f : fields(t)) {
        if (!firstField) s += ", ";
        firstField = false;
        s += name(f);
      }
      return s + ")";
    }
  }
  return "?";
}

}  // namespace meldvm
