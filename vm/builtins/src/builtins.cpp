// The implementations of the §5.6 built-ins, by id (builtins.def), and calling one by name.
#include "meldvm/builtins.hpp"

#include <string>

namespace meldvm {

Value callBuiltin(BuiltinContext& ctx, std::string_view name, std::span<const Value> args, TypeId result) {
  const BuiltinInfo* b = findBuiltin(name);
  if (!b) throw RuntimeError("unknown built-in function '" + std::string(name) + "'");
  if (args.size() != b->arity)
    throw RuntimeError(std::string(name) + ": expects " + std::to_string(b->arity) + " arguments");
  return builtinFunction(b->id)(ctx, args, result);
}

}  // namespace meldvm
