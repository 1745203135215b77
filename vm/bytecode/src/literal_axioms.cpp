#include "meldvm/literal_axioms.hpp"

#include <stdexcept>

#include "meldvm/bytecode_internal.hpp"
#include "meldvm/program.hpp"

namespace meldvm {

void LiteralAxioms::add(std::span<const std::uint32_t> code, std::string_view label) {
  code_.insert(code_.end(), code.begin(), code.end());
  codeStart_.push_back(code_.size());
  labels_.append(label);
  labelStart_.push_back(labels_.size());
}

void LiteralAxioms::addLines(std::span<const SourceLine> lines) {
  if (lineStart_.size() > size()) throw std::logic_error("meldvm: source lines for a block not added");
  lines_.insert(lines_.end(), lines.begin(), lines.end());
  lineStart_.push_back(lines_.size());
}

CodeBlock LiteralAxioms::block(std::size_t i) const {
  CodeBlock b;
  b.code.assign(code(i).begin(), code(i).end());
  b.label = label(i);
  b.lines.assign(lines(i).begin(), lines(i).end());
  return b;
}

namespace detail {

bool literalAxiomCode(std::span<const std::uint32_t> code) {
  for (std::size_t pos = 0; pos < code.size();) {
    if (Opcode(code[pos]) == Opcode::RET) return pos + 1 == code.size();
    const std::size_t len = axiomFactsLength(code, pos);
    if (len == 0) return false;
    pos += len;
  }
  return false;  // no RET
}

}  // namespace detail
}  // namespace meldvm
