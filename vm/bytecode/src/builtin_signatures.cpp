// The signatures of the built-in functions (builtins.def), look-up and type resolution.
#include "meldvm/builtin_signatures.hpp"

#include <stdexcept>

namespace meldvm {

namespace {

using enum Sig;

// One type letter (or letter pair) of a builtins.def signature.
constexpr Sig parseSig(std::string_view& s) {
  const char c = s.front();
  s.remove_prefix(1);
  const char e = s.empty() ? '\0' : s.front();
  auto container = [&](Sig ofInt, Sig ofFloat, Sig ofT) {
    s.remove_prefix(1);
    if (e == 'i' && ofInt != T) return ofInt;
    if (e == 'f' && ofFloat != T) return ofFloat;
    if (e == 'T') return ofT;
    throw std::logic_error("builtins.def: no such container type");
  };
  switch (c) {
    case 'i':
      return Int;
    case 'f':
      return Float;
    case 'b':
      return Bool;
    case 'n':
      return Node;
    case 't':
      return Thread;
    case 's':
      return String;
    case 'T':
      return T;
    case 'R':
      return Struct;
    case 'Q':
      return Struct2;
    case 'L':
      return container(ListInt, ListFloat, ListT);
    case 'A':
      return container(ArrayInt, T, ArrayT);
    case 'S':
      return container(T, T, SetT);
  }
  throw std::logic_error("builtins.def: no such type letter");
}

constexpr BuiltinInfo makeInfo(std::uint16_t id, std::string_view name, std::string_view signature,
                               bool typeArg) {
  BuiltinInfo info{id, name, signature, 0, {}, Int, typeArg};
  std::string_view s = signature;
  while (s.front() != '>') {
    if (info.arity == info.args.size()) throw std::logic_error("builtins.def: too many parameters");
    info.args[info.arity++] = parseSig(s);
    if (s.front() == ',') s.remove_prefix(1);
  }
  s.remove_prefix(1);
  info.result = parseSig(s);
  if (!s.empty()) throw std::logic_error("builtins.def: text after the result");
  return info;
}

constexpr BuiltinInfo kTable[] = {
#define BUILTIN(ID, NAME, IMPL, SIG, TYPE_ARG) makeInfo(ID, NAME, SIG, TYPE_ARG),
#include "meldvm/builtins.def"
#undef BUILTIN
};

constexpr bool idsAreDense() {
  for (std::size_t i = 0; i < std::size(kTable); ++i)
    if (kTable[i].id != i) return false;
  return true;
}
static_assert(idsAreDense(), "builtins.def: ids must be 0, 1, 2, ... in order");

// Binds T from one argument type against its pattern; false on a mismatch.
bool bind(const TypeTable& types, Sig s, TypeId t, std::optional<TypeId>& tvar) {
  auto fixed = [&](TypeId want) { return t == want; };
  auto var = [&](TypeId elem) {
    if (tvar && *tvar != elem) return false;
    tvar = elem;
    return true;
  };
  switch (s) {
    case Int:
      return fixed(TypeTable::kInt);
    case Float:
      return fixed(TypeTable::kFloat);
    case Bool:
      return fixed(TypeTable::kBool);
    case Node:
      return fixed(TypeTable::kNode);
    case Thread:
      return fixed(TypeTable::kThread);
    case String:
      return fixed(TypeTable::kString);
    case ListInt:
      return types.kind(t) == TypeKind::List && types.element(t) == TypeTable::kInt;
    case ListFloat:
      return types.kind(t) == TypeKind::List && types.element(t) == TypeTable::kFloat;
    case ArrayInt:
      return types.kind(t) == TypeKind::Array && types.element(t) == TypeTable::kInt;
    case ListT:
      return types.kind(t) == TypeKind::List && var(types.element(t));
    case ArrayT:
      return types.kind(t) == TypeKind::Array && var(types.element(t));
    case SetT:
      return types.kind(t) == TypeKind::Set && var(types.element(t));
    case T:
      return var(t);
    case Struct:
    case Struct2: {
      if (types.kind(t) != TypeKind::Struct) return false;
      for (TypeId f : types.fields(t))
        if (f != TypeTable::kFloat) return false;
      return true;
    }
  }
  return false;
}

}  // namespace

std::span<const BuiltinInfo> builtinTable() { return kTable; }

const BuiltinInfo* findBuiltin(std::string_view name) {
  for (const BuiltinInfo& b : kTable)
    if (b.name == name) return &b;
  return nullptr;
}

const BuiltinInfo* findBuiltin(std::uint16_t id) { return id < kBuiltinIdCount ? &kTable[id] : nullptr; }

bool callTypesMatch(const TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes,
                    TypeId result) {
  if (argTypes.size() != b.arity) return false;
  std::optional<TypeId> tvar;
  for (std::size_t i = 0; i < b.arity; ++i)
    if (!bind(types, b.args[i], argTypes[i], tvar)) return false;
  switch (b.result) {
    case Struct:
      return result == argTypes[0];
    case Struct2:
      return result == argTypes[1];
    case T:
      return !tvar || *tvar == result;
    default:  // a fixed type, or a container of T: the same patterns as the arguments
      return bind(types, b.result, result, tvar);
  }
}

std::optional<TypeId> resolveResult(TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes,
                                    std::optional<TypeId> hint) {
  if (argTypes.size() != b.arity) return std::nullopt;
  std::optional<TypeId> tvar;
  for (std::size_t i = 0; i < b.arity; ++i)
    if (!bind(types, b.args[i], argTypes[i], tvar)) return std::nullopt;
  if (!tvar) tvar = hint;
  switch (b.result) {
    case Int:
      return TypeTable::kInt;
    case Float:
      return TypeTable::kFloat;
    case Bool:
      return TypeTable::kBool;
    case Node:
      return TypeTable::kNode;
    case Thread:
      return TypeTable::kThread;
    case String:
      return TypeTable::kString;
    case ListInt:
      return types.list(TypeTable::kInt);
    case ListFloat:
      return types.list(TypeTable::kFloat);
    case ArrayInt:
      return types.array(TypeTable::kInt);
    case Struct:
      return argTypes[0];
    case Struct2:
      return argTypes[1];
    case T:
      return tvar;
    case ListT:
      return tvar ? std::optional<TypeId>(types.list(*tvar)) : std::nullopt;
    case ArrayT:
      return tvar ? std::optional<TypeId>(types.array(*tvar)) : std::nullopt;
    case SetT:
      return tvar ? std::optional<TypeId>(types.set(*tvar)) : std::nullopt;
  }
  return std::nullopt;
}

}  // namespace meldvm
