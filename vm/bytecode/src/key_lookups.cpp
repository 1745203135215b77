// The look-ups by key of a program (bytecode_internal.hpp): which (predicate, argument) pairs the
// VM indexes, and which loop bodies begin with a look-up of their fact's argument.
#include <optional>
#include <string>

#include "meldvm/bytecode_internal.hpp"

namespace meldvm::detail {

std::vector<std::pair<PredId, std::uint32_t>> keyLookups(const Program& program) {
  std::vector<std::pair<PredId, std::uint32_t>> out;
  for (const IndexRequest& ix : program.indexes)
    if (ix.predicate < program.predicates.size() && ix.field < program.predicates[ix.predicate].arity())
      out.emplace_back(ix.predicate, ix.field);
  auto scan = [&](const CodeBlock& b) {
    forEachInstruction(b.code, [&](std::size_t pc) {
      if (Opcode(b.code[pc]) == Opcode::ITER_KEY) out.emplace_back(b.code[pc + 1], b.code[pc + 4]);
    });
  };
  for (const Rule& r : program.rules) scan(r.block);
  for (const Process& p : program.processes) scan(p.block);
  for (const Function& f : program.functions) scan(f.block);
  return out;
}

std::optional<KeyJoin> keyJoinAt(std::span<const std::uint32_t> code, std::size_t body, std::uint32_t slot) {
  std::string why;
  std::size_t pc = body;
  for (std::size_t len; pc < code.size() && Opcode(code[pc]) == Opcode::LOAD && code[pc + 1] == slot;
       pc += len)
    if ((len = instructionLength(code, pc, why)) == 0) return std::nullopt;
  if (pc >= code.size() || Opcode(code[pc]) != Opcode::ITER_KEY || (code[pc + 3] & kIterThread))
    return std::nullopt;
  // The ITER_KEY's key register, loaded from the fact by the last LOAD into it.
  std::optional<std::uint32_t> field;
  for (std::size_t at = body; at < pc; at += instructionLength(code, at, why))
    if (code[at + 3] == code[pc + 5]) field = code[at + 2];
  if (!field) return std::nullopt;
  return KeyJoin{*field, code[pc + 1], code[pc + 4]};
}

}  // namespace meldvm::detail
