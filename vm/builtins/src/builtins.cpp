// The table of §5.6 built-ins, lookup and type resolution.
#include "meldvm/builtins.hpp"

#include <algorithm>

namespace meldvm {

namespace {

using enum Sig;
namespace b = builtins;

constexpr BuiltinInfo E(std::uint16_t id, std::string_view name, std::initializer_list<Sig> args, Sig result,
                        bool typeArg, BuiltinFn fn) {
  BuiltinInfo info{id, name, std::uint8_t(args.size()), {}, result, typeArg, fn};
  std::size_t i = 0;
  for (Sig s : args) info.args[i++] = s;
  return info;
}

const BuiltinInfo kTable[] = {
    E(0, "sigmoid", {Float}, Float, false, b::sigmoid),
    E(1, "randint", {Int}, Int, false, b::randint),
    E(2, "normalize", {ListFloat}, ListFloat, false, b::normalize),
    E(3, "damp", {ListFloat, ListFloat, Float}, ListFloat, false, b::damp),
    E(4, "divide", {ListFloat, ListFloat}, ListFloat, false, b::divide),
    E(5, "convolve", {ListFloat, ListFloat}, ListFloat, false, b::convolve),
    E(6, "addfloatlists", {ListFloat, ListFloat}, ListFloat, false, b::addfloatlists),
    E(7, "intlistdiff", {ListInt, ListInt}, ListInt, false, b::intlistdiff),
    E(8, "lnth", {ListT, Int}, T, false, b::lnth),
    E(9, "concatenate", {String, String}, String, false, b::concatenate),
    E(10, "str2float", {String}, Float, false, b::str2float),
    E(11, "str2int", {String}, Int, false, b::str2int),
    E(12, "lremove", {ListT, T}, ListT, true, b::lremove),
    E(13, "wastetime", {Int}, Int, false, b::wastetime),
    E(14, "truncate", {Float, Int}, Float, false, b::truncate),
    E(15, "float2int", {Float}, Int, false, b::float2int),
    E(16, "int2str", {Int}, String, false, b::int2str),
    E(17, "float2str", {Float}, String, false, b::float2str),
    E(18, "intlistsub", {ListInt, Int, Int}, ListInt, false, b::intlistsub),
    E(19, "str2intlist", {String}, ListInt, false, b::str2intlist),
    E(20, "filecountwords", {String, Int}, Int, false, b::filecountwords),
    E(21, "residual", {ListFloat, ListFloat}, Float, false, b::residual),
    E(22, "llength", {ListT}, Int, false, b::llength),
    E(23, "lappend", {ListT, ListT}, ListT, true, b::lappend),
    E(24, "priority", {Node}, Float, false, b::priority),
    E(25, "lreverse", {ListT}, ListT, true, b::lreverse),
    E(26, "llast", {ListT}, T, false, b::llast),
    E(27, "cpu-id", {Node}, Thread, false, b::cpu_id),
    E(28, "node2int", {Node}, Int, false, b::node2int),
    E(29, "intpower", {Int, Int}, Int, false, b::intpower),
    E(30, "lsort", {ListT}, ListT, true, b::lsort),
    E(31, "lremoveduplicates", {ListT}, ListT, true, b::lremoveduplicates),
    E(32, "degeneratevector", {Int, Int}, ListInt, false, b::degeneratevector),
    E(33, "demergemessages", {ListInt, ListInt}, ListInt, false, b::demergemessages),
    E(34, "intlistequal", {ListInt, ListInt}, Int, false, b::intlistequal),
    E(35, "addfloatstructs", {Struct, Struct}, Struct, true, b::addfloatstructs),
    E(36, "normalizestruct", {Struct}, Struct, true, b::normalizestruct),
    E(37, "dampstruct", {Struct, Struct, Float}, Struct, true, b::dampstruct),
    E(38, "residualstruct", {Struct, Struct}, Float, true, b::residualstruct),
    E(39, "dividestruct", {Struct, Struct}, Struct, true, b::dividestruct),
    E(40, "convolvestruct", {Struct, Struct}, Struct2, true, b::convolvestruct),
    E(41, "cpu-static", {Node}, Int, false, b::cpu_static),
    E(42, "is-moving", {Node}, Bool, false, b::is_moving),
    E(43, "is-static", {Node}, Bool, false, b::is_static),
    E(44, "partition_vertical", {Int, Int, Int, Int}, Thread, false, b::partition_vertical),
    E(45, "partition_horizontal", {Int, Int, Int, Int}, Thread, false, b::partition_horizontal),
    E(46, "partition_grid", {Int, Int, Int, Int}, Thread, false, b::partition_grid),
    E(47, "queue-size", {Node}, Int, false, b::queue_size),
    E(48, "facts-proved", {Node}, Int, false, b::facts_proved),
    E(49, "facts-consumed", {Node}, Int, false, b::facts_consumed),
    E(50, "lcount", {ListT, T}, Int, true, b::lcount),
    E(51, "lexists", {ListT, T}, Bool, true, b::lexists),
    E(52, "lexistss", {ListT, ListT}, Bool, true, b::lexistss),
    E(53, "queens_violation", {Int, ListInt}, Bool, false, b::queens_violation),
    E(54, "minimax_score", {ListInt, Int, Int}, Int, false, b::minimax_score),
    E(55, "minimax_points", {ListInt, Int}, Int, false, b::minimax_points),
    E(56, "array_init", {Int, T}, ArrayT, true, b::array_init),
    E(57, "array_get", {ArrayT, Int}, T, false, b::array_get),
    E(58, "array_set", {ArrayT, Int, T}, ArrayT, true, b::array_set),
    E(59, "array_add", {ArrayT, T}, ArrayT, true, b::array_add),
    E(60, "array_from_list", {ListT}, ArrayT, true, b::array_from_list),
    E(61, "array_size", {ArrayT}, Int, false, b::array_size),
    E(62, "minimax_score2", {ArrayInt, Int, Int}, Int, false, b::minimax_score2),
    E(63, "minimax_points2", {ArrayInt, Int}, Int, false, b::minimax_points2),
    E(64, "fabs", {Float}, Float, false, b::fabs),
    // Sets and arrays share the tuple representation (the heap keeps a set's items unique), so the
    // set functions are the array ones.
    E(65, "set_size", {SetT}, Int, false, b::array_size),
    E(66, "set_exists", {SetT, T}, Bool, true, b::array_exists),
    E(67, "set_add", {SetT, T}, SetT, true, b::array_add),
    E(68, "set_from_list", {ListT}, SetT, true, b::array_from_list),
    E(69, "array_exists", {ArrayT, T}, Bool, true, b::array_exists),
    E(70, "ltake", {ListT, Int}, ListT, false, b::ltake),
};

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

const BuiltinInfo* findBuiltin(std::uint16_t id) {
  const auto it = std::lower_bound(std::begin(kTable), std::end(kTable), id,
                                   [](const BuiltinInfo& b, std::uint16_t i) { return b.id < i; });
  return it != std::end(kTable) && it->id == id ? &*it : nullptr;
}

bool callTypesMatch(const TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes, TypeId result) {
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

Value callBuiltin(BuiltinContext& ctx, std::string_view name, std::span<const Value> args, TypeId result) {
  const BuiltinInfo* b = findBuiltin(name);
  if (!b) throw RuntimeError("unknown built-in function '" + std::string(name) + "'");
  if (args.size() != b->arity)
    throw RuntimeError(std::string(name) + ": expects " + std::to_string(b->arity) + " arguments");
  return b->fn(ctx, args, result);
}

}  // namespace meldvm
