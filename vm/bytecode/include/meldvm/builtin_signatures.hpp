// What the bytecode knows of the built-in functions of §5.6: their ids, names and type signatures,
// read from builtins.def. The verifier checks a CALL against them and meldc resolves a call's
// result type with them; the implementations are the VM's (builtins.hpp), so a program that only
// compiles or checks bytecode does not link them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "meldvm/types.hpp"

namespace meldvm {

// Argument / result type patterns (the letters of builtins.def). `T` is the one type variable of a
// polymorphic entry; `Struct` is any struct of floats, and a `Struct` result has the type of the
// first argument (`Struct2`: of the second argument, for convolvestruct).
enum class Sig : std::uint8_t {
  Int,
  Float,
  Bool,
  Node,
  Thread,
  String,
  ListInt,
  ListFloat,
  ListT,
  T,
  ArrayInt,
  ArrayT,
  SetT,
  Struct,
  Struct2
};

struct BuiltinInfo {
  std::uint16_t id;            // bytecode CALL operand
  std::string_view name;       // as written in source, e.g. "lnth", "cpu-id"
  std::string_view signature;  // as in builtins.def, e.g. "LT,i>T"
  std::uint8_t arity;
  std::array<Sig, 4> args;
  Sig result;
  bool typeArg;  // "+type": the compiler passes the element type as a hidden argument
};

// Ids are dense: every id below this one is a built-in (the first user extern id).
inline constexpr std::uint16_t kBuiltinIdCount = 0
#define BUILTIN(ID, NAME, IMPL, SIG, TYPE_ARG) +1
#include "meldvm/builtins.def"
#undef BUILTIN
    ;

// Every built-in, in id order.
std::span<const BuiltinInfo> builtinTable();
const BuiltinInfo* findBuiltin(std::string_view name);
const BuiltinInfo* findBuiltin(std::uint16_t id);

// The concrete result type of a call with these argument types, or nullopt if they do not match
// the entry's signature (wrong count, wrong type, inconsistent T). `hint` supplies T when no
// argument fixes it (e.g. the expected type of `array_from_list([])` at the call site).
std::optional<TypeId> resolveResult(TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes,
                                    std::optional<TypeId> hint = std::nullopt);

// Whether a call with these argument types can have the concrete result type `result` (the
// verifier's check of a CALL: the interpreter trusts the types of its registers).
bool callTypesMatch(const TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes,
                    TypeId result);

}  // namespace meldvm
