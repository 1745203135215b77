// Which loops read the lists of the facts they visit (bytecode_internal.hpp): the interpreter and
// native code fetch those lists ahead.
#include <algorithm>

#include "meldvm/bytecode_internal.hpp"

namespace meldvm::detail {

std::int32_t firstListField(const Program& program, PredId p) {
  const PredicateDesc& d = program.predicates[p];
  for (std::uint32_t i = 0; i < d.arity(); ++i)
    if (program.predicates.types().kind(d.fields[i]) == TypeKind::List) return std::int32_t(i);
  return -1;
}

bool loopReadsLists(const Program& program, std::span<const std::uint32_t> code, std::size_t loopPc) {
  if (Opcode(code[loopPc]) != Opcode::ITER || !(code[loopPc + 3] & kIterLinear)) return false;
  const std::uint32_t slot = code[loopPc + 2];
  const std::int32_t field = firstListField(program, code[loopPc + 1]);
  if (field < 0) return false;
  const std::span<const std::uint32_t> body =
      code.first(std::min<std::size_t>(code[loopPc + 4], code.size()));
  std::string why;
  for (std::size_t pc = loopPc + 5, len; pc < body.size(); pc += len) {
    if (Opcode(code[pc]) == Opcode::LOAD && code[pc + 1] == slot && code[pc + 2] == std::uint32_t(field))
      return true;
    if ((len = instructionLength(body, pc, why)) == 0) return false;
  }
  return false;
}

}  // namespace meldvm::detail
