#include "meldc/builtins.hpp"

#include "meldvm/builtin_signatures.hpp"

namespace meldc {

const std::vector<BuiltinPredicate>& builtinPredicates() {
  using K = BuiltinPredKind;
  static const std::vector<BuiltinPredicate> table = {
      {"_init", K::Linear, false, false, "n"},
      {"_init_thread", K::Linear, false, true, "t"},
      {"setcolor", K::Linear, true, false, "n,i,i,i"},
      {"setedgelabel", K::Linear, true, false, "n,n,s"},
      {"write-string", K::Linear, true, false, "n,s"},
      {"setcolor2", K::Persistent, true, false, "n,i"},
      {"stop-program", K::Instruction, false, false, "n"},
      {"set-priority", K::Instruction, false, false, "n,f"},
      {"add-priority", K::Instruction, false, false, "n,f"},
      {"remove-priority", K::Instruction, false, false, "n"},
      {"schedule-next", K::Instruction, false, false, "n"},
      {"set-default-priority", K::Instruction, false, false, "n,f"},
      {"set-static", K::Instruction, false, false, "n"},
      {"set-moving", K::Instruction, false, false, "n"},
      {"set-affinity", K::Instruction, false, false, "n,n"},
      {"set-cpu", K::Instruction, false, false, "n,t"},
      {"just-moved", K::Linear, false, false, "n"},
      {"thread-list", K::Persistent, false, true, "t,Lt"},
      {"other-thread", K::Persistent, false, true, "t,t,i"},
      {"leader-thread", K::Persistent, false, true, "t,t"},
  };
  return table;
}

const std::vector<BuiltinFunction>& builtinFunctions() {
  static const std::vector<BuiltinFunction> table = [] {
    std::vector<BuiltinFunction> t;
    for (const meldvm::BuiltinInfo& b : meldvm::builtinTable()) t.push_back({b.name, b.arity, b.signature});
    return t;
  }();
  return table;
}

const BuiltinPredicate* findBuiltinPredicate(std::string_view name) {
  for (const BuiltinPredicate& b : builtinPredicates())
    if (b.name == name) return &b;
  return nullptr;
}

const BuiltinFunction* findBuiltinFunction(std::string_view name) {
  const meldvm::BuiltinInfo* b = meldvm::findBuiltin(name);
  return b ? &builtinFunctions()[b->id] : nullptr;
}

}  // namespace meldc
