// The names the compiler knows without a declaration: built-in predicates (§4.1.3) and built-in
// external functions (§5.6, in table order: the position is the function id).
#pragma once

#include <string_view>
#include <vector>

namespace meldc {

enum class BuiltinPredKind { Linear, Persistent, Instruction };

struct BuiltinPredicate {
  std::string_view name;  // lower case
  int arity;              // including the home argument
  BuiltinPredKind kind;
  bool action;
  bool thread;  // home is a thread
};

struct BuiltinFunction {
  std::string_view name;
  int arity;
};

const std::vector<BuiltinPredicate>& builtinPredicates();
const std::vector<BuiltinFunction>& builtinFunctions();  // index = function id

}  // namespace meldc
