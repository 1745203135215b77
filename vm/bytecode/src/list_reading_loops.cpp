// Which loops read the lists of the facts they visit (bytecode_internal.hpp): the interpreter and
// native code fetch those lists ahead; and which registers a loop keeps (native code computes what
// depends on them once per run of the loop).
#include <algorithm>
#include <string_view>
#include <vector>

#include "meldvm/bytecode_internal.hpp"

namespace meldvm::detail {

std::int32_t firstListField(const Program& program, PredId p) {
  const PredicateDesc& d = program.predicates[p];
  for (std::uint32_t i = 0; i < d.arity(); ++i)
    if (program.predicates.types().kind(d.fields[i]) == TypeKind::List) return std::int32_t(i);
  return -1;
}

int listFetchDepth(const Program& program, std::span<const std::uint32_t> code, std::size_t loopPc) {
  if (Opcode(code[loopPc]) != Opcode::ITER || !(code[loopPc + 3] & kIterLinear)) return -1;
  const std::uint32_t slot = code[loopPc + 2];
  const std::int32_t field = firstListField(program, code[loopPc + 1]);
  if (field < 0) return -1;
  const std::span<const std::uint32_t> body =
      code.first(std::min<std::size_t>(code[loopPc + 4], code.size()));
  std::vector<std::uint32_t> listRegs;  // the registers the body loads the list into
  std::string why;
  for (std::size_t pc = loopPc + 5, len; pc < body.size(); pc += len) {
    const auto op = Opcode(code[pc]);
    if (op == Opcode::LOAD && code[pc + 1] == slot && code[pc + 2] == std::uint32_t(field))
      listRegs.push_back(code[pc + 3]);
    if (op == Opcode::CALL || op == Opcode::CALLF) {  // operands: r0, B or U, (T,) count, registers
      const std::size_t first = op == Opcode::CALL ? 5 : 4;
      for (std::size_t a = 0; a < code[pc + first - 1]; ++a)
        if (std::find(listRegs.begin(), listRegs.end(), code[pc + first + a]) != listRegs.end())
          return kListFetchAhead - 1;
    }
    if ((len = instructionLength(body, pc, why)) == 0) break;
  }
  return listRegs.empty() ? -1 : 0;
}

bool listsStayPut(std::span<const std::uint32_t> code) {
  bool put = true;
  forEachInstruction(code, [&](std::size_t pc) { put = put && Opcode(code[pc]) != Opcode::UPDATE; });
  return put;
}

std::int64_t writtenRegister(std::span<const std::uint32_t> code, std::size_t pos) {
  const auto op = Opcode(code[pos]);
  const int operand = writtenRegisterOperand(op);
  if (operand < 0) return -1;
  // The written register comes before any variable-length operand list ('*').
  const std::string_view letters = opcodeInfo(op).operands;
  std::size_t w = pos + 1;
  for (int i = 0; i < operand; ++i) w += letters[std::size_t(i)] == 'D' ? 2 : 1;
  return code[w];
}

std::int64_t outermostLoopKeeping(std::span<const std::uint32_t> code, std::size_t pos, std::uint32_t r) {
  // Loops nest, so the loops around pos that keep r are the innermost ones: the outermost of
  // them is the first loop around pos (in code order) that keeps it.
  std::string why;
  std::int64_t found = -1;
  forEachInstruction(code, [&](std::size_t loop) {
    if (found >= 0 || loop >= pos || !isLoop(code[loop])) return;
    const std::size_t len = instructionLength(code, loop, why);
    const std::size_t end = std::min<std::size_t>(code[loop + len - 1], code.size());  // after its NEXT
    if (end <= pos) return;
    bool keeps = true;
    for (std::size_t at = loop; at < end && keeps; at += instructionLength(code, at, why))
      keeps = writtenRegister(code, at) != std::int64_t(r);
    if (keeps) found = std::int64_t(loop);
  });
  return found;
}

}  // namespace meldvm::detail
