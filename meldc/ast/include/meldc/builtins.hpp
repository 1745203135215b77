// The names the compiler knows without a declaration: built-in predicates (§4.1.3) and built-in
// external functions (§5.6, in table order: the position is the function id).
#pragma once

#include <algorithm>
#include <string_view>
#include <vector>

namespace meldc {

enum class BuiltinPredKind { Linear, Persistent, Instruction };

struct BuiltinPredicate {
  std::string_view name;  // lower case
  BuiltinPredKind kind;
  bool action;
  bool thread;              // home is a thread
  std::string_view fields;  // field types, home included, in builtins.def's notation ("n,i,i,i")
  int arity() const { return 1 + int(std::count(fields.begin(), fields.end(), ',')); }  // home included
};

// The built-in functions are meldvm's table (vm/bytecode/include/meldvm/builtins.def), which the
// VM's verifier and interpreter read too.
struct BuiltinFunction {
  std::string_view name;
  int arity;
  std::string_view signature;  // builtins.def's notation: "LT,i>T"
};

const std::vector<BuiltinPredicate>& builtinPredicates();
const std::vector<BuiltinFunction>& builtinFunctions();               // index = function id
const BuiltinPredicate* findBuiltinPredicate(std::string_view name);  // nullptr: not built in
const BuiltinFunction* findBuiltinFunction(std::string_view name);

}  // namespace meldc
