// Which loop bodies begin with a look-up of the loop fact's argument in an index
// (bytecode_internal.hpp's keyJoinAt).
#include "meldvm/bytecode_internal.hpp"

namespace meldvm::detail {

std::optional<KeyJoin> keyJoinAt(std::span<const std::uint32_t> code, std::size_t body, std::uint32_t slot) {
  // (No allocation: the interpreter asks as it opens such a loop.)
  constexpr std::size_t kLoadLength = 4;  // LOAD S F r
  std::size_t pc = body;
  while (pc + kLoadLength <= code.size() && Opcode(code[pc]) == Opcode::LOAD && code[pc + 1] == slot)
    pc += kLoadLength;
  if (pc + 6 >= code.size() || Opcode(code[pc]) != Opcode::ITER_KEY || (code[pc + 3] & kIterThread))
    return std::nullopt;
  const std::uint32_t key = code[pc + 5];
  std::optional<std::uint32_t> field;
  for (std::size_t at = body; at < pc; at += kLoadLength)
    if (code[at + 3] == key) field = code[at + 2];  // the last load into it counts
  if (!field) return std::nullopt;
  return KeyJoin{*field, code[pc + 1], code[pc + 4]};
}

}  // namespace meldvm::detail
