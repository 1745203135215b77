// The interpreter's axioms (§6.2): AXIOM_FACTS in an axiom block, and the blocks of literal facts
// only (Program::literalAxioms) that AXIOMS runs straight from their array. A node's facts of one
// predicate go to the store together (Machine::deriveEach) unless derivations are recorded.
#include "interpreter.hpp"
#include "meldvm/bytecode_internal.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

void Interpreter::axiomFacts(const Frame& f, std::uint32_t pc) {
  if (machine_.derivations_ || f.negative) [[unlikely]]
    return axiomFactsOneByOne(f.code, pc, f.host, f.negative, [&](std::uint32_t at, const Value* args) {
      noteDerivation(f, at, f.host, f.code[pc + 1], args);
    });
  axiomFactsTogether(f.code + pc, f.host);
}

void Interpreter::axiomFactsTogether(const std::uint32_t* c, NodeId host) {
  const PredId p = c[1];
  const std::span<const TypeId> fields = program_.predicates[p].fields;
  const std::size_t facts = std::size_t(c[2]) / detail::axiomFactWords(fields);
  if (facts * fields.size() > args_.size()) growArgs(std::uint32_t(facts * fields.size()));
  Value* out = args_.data();
  for (const std::uint32_t *w = c + 3, *end = w + c[2]; w != end;)
    for (const TypeId t : fields) *out++ = detail::axiomField(t, w);
  machine_.deriveEach(host, p, args_.data(), std::uint32_t(facts));
}

template <class Note>
void Interpreter::axiomFactsOneByOne(const std::uint32_t* code, std::uint32_t pc, NodeId host, bool negative,
                                     Note&& note) {
  const std::uint32_t* c = code + pc;
  const PredId p = c[1];
  const std::span<const TypeId> fields = program_.predicates[p].fields;
  if (fields.size() > args_.size()) growArgs(std::uint32_t(fields.size()));
  for (const std::uint32_t *w = c + 3, *end = w + c[2]; w != end;) {
    const auto at = std::uint32_t(w - code);  // a fact's line: the one at its first data word
    for (std::size_t i = 0; i < fields.size(); ++i) args_[i] = detail::axiomField(fields[i], w);
    if (machine_.derivations_ && !negative) note(at, args_.data());
    machine_.derive(host, p, args_.data(), negative);
  }
}

void Interpreter::runLiteralAxioms(std::size_t i, NodeId host) {
  const std::span<const std::uint32_t> code = program_.literalAxioms.code(i);
  // Verified: AXIOM_FACTS instructions (3 words and their data), then a RET.
  for (std::uint32_t pc = 0; Opcode(code[pc]) == Opcode::AXIOM_FACTS; pc += 3 + code[pc + 2]) {
    if (!machine_.derivations_) {
      axiomFactsTogether(code.data() + pc, host);
      continue;
    }
    axiomFactsOneByOne(code.data(), pc, host, false, [&](std::uint32_t at, const Value* args) {
      const LiteralAxioms& axioms = program_.literalAxioms;
      record(derivation(true, axioms.label(i), axioms.lines(i), at, host), host, code[pc + 1], args);
    });
  }
}

}  // namespace meldvm
