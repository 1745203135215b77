// Type expressions as written in declarations (§3.1): int, float, list T, :(T1, T2), aliases...
#pragma once

#include <string>
#include <vector>

#include "meldc/ast/symbol.hpp"
#include "meldc/source.hpp"

namespace meldc::ast {

enum class TypeKind { Int, Float, Bool, String, Node, Thread, Named, List, Set, Array, Struct };

struct TypeExpr {
  TypeKind kind = TypeKind::Int;
  SourceLoc loc;
  std::string name;            // Named: a type alias or a node subtype
  std::vector<TypeExpr> args;  // List/Set/Array: one element type; Struct: the fields
  Symbol sym;                  // Named: the folded name
};

}  // namespace meldc::ast
