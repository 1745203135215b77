#include "meldvm/program_tables.hpp"

#include <algorithm>

#include "meldvm/bytecode_internal.hpp"

namespace meldvm {

namespace {

void perPredicate(ProgramTables& t, const Program& program) {
  const std::size_t preds = program.predicates.size();
  t.rulesOf.resize(preds);
  t.processesOf.resize(preds);
  for (std::uint32_t r = 0; r < program.rules.size(); ++r)
    for (PredId p : program.rules[r].bodyPredicates) t.rulesOf[p].push_back(r);
  for (std::uint32_t i = 0; i < program.processes.size(); ++i)
    t.processesOf[program.processes[i].trigger].push_back(i);
  for (PredId p = 0; p < preds; ++p) {
    const PredicateDesc& d = program.predicates[p];
    t.maxArity = std::max(t.maxArity, d.arity());
    t.queuedPersistent.push_back(!d.linear && (!t.processesOf[p].empty() || d.aggregated()));
    t.isLinear.push_back(d.linear);
    t.plainLinear.push_back(d.linear && !d.action);
    t.arity.push_back(d.arity());
    t.listField.push_back(detail::firstListField(program, p));
    t.linearLists = t.linearLists || (d.linear && t.listField.back() >= 0);
    t.isThreadPred.push_back(d.thread);
    t.hasThreads = t.hasThreads || d.thread;
  }
  t.justMoved = program.predicates.find("just-moved");
  if (t.justMoved == preds) t.justMoved = Program::kNoPred;
}

// One walk over the code: what processes read, whether random numbers are drawn; and the key look-ups.
void scanCode(ProgramTables& t, const Program& program) {
  t.processNeeds.resize(program.processes.size());
  for (std::uint32_t i = 0; i < program.processes.size(); ++i) {
    const std::vector<std::uint32_t>& code = program.processes[i].block.code;
    detail::forEachInstruction(code, [&](std::size_t pc) {
      if (detail::isLoop(code[pc]) && !(code[pc + 3] & kIterThread))
        t.processNeeds[i].push_back(code[pc + 1]);
    });
  }
  t.keyLookups = detail::keyLookups(program);
  auto scan = [&](const CodeBlock& b) {
    detail::forEachInstruction(b.code, [&](std::size_t pc) {
      const auto op = Opcode(b.code[pc]);
      if (op == Opcode::NEWNODE) t.createsNodes = true;
      if ((op == Opcode::CALL && (b.code[pc + 2] == 1 || b.code[pc + 2] == 32)) ||
          (op == Opcode::ITER_SORTED && (b.code[pc + 3] & kIterRandom)))
        t.usesRandom = true;
    });
  };
  for (const Rule& r : program.rules) scan(r.block);
  for (const Process& p : program.processes) scan(p.block);
  for (const Function& f : program.functions) scan(f.block);
}

void ruleTriggers(ProgramTables& t, const Program& program) {
  std::vector<std::uint32_t> needsFrom, needCount;
  for (const Rule& r : program.rules) {
    needsFrom.push_back(std::uint32_t(t.needs.size()));
    for (PredId q : r.bodyPredicates)
      if (std::find(t.needs.begin() + needsFrom.back(), t.needs.end(), q) == t.needs.end())
        t.needs.push_back(q);
    needCount.push_back(std::uint32_t(t.needs.size()) - needsFrom.back());
  }
  for (PredId p = 0; p < t.rulesOf.size(); ++p) {
    t.triggersFrom.push_back(std::uint32_t(t.triggers.size()));
    for (std::uint32_t r : t.rulesOf[p]) {
      if (!t.triggers.empty() && t.triggersFrom.back() < t.triggers.size() && t.triggers.back().rule == r)
        continue;  // p twice in the body
      bool threadFacts = false;
      for (std::uint32_t i = 0; i < needCount[r]; ++i)
        threadFacts = threadFacts || t.isThreadPred[t.needs[needsFrom[r] + i]];
      t.triggers.push_back(
          {std::uint64_t(1) << (r % 64), r / 64, r, needsFrom[r], needCount[r], threadFacts});
    }
  }
  t.triggersFrom.push_back(std::uint32_t(t.triggers.size()));
  t.triggerBits.assign(t.rulesOf.size(), 0);
  for (PredId p = 0; p < t.rulesOf.size(); ++p)
    for (std::uint32_t i = t.triggersFrom[p]; i < t.triggersFrom[p + 1]; ++i)
      if (t.triggers[i].word == 0) t.triggerBits[p] |= t.triggers[i].bit;
}

}  // namespace

ProgramTables::ProgramTables(const Program& program) {
  perPredicate(*this, program);
  scanCode(*this, program);
  ruleTriggers(*this, program);
  for (std::uint32_t r = 0; r < program.rules.size(); ++r) {
    bool node = false, thread = false;
    for (PredId p : program.rules[r].bodyPredicates) (isThreadPred[p] ? thread : node) = true;
    if (node && thread) mixedRules.push_back(r);
    if (thread && !node) threadRules.push_back(r);
    isMixedRule.push_back(node && thread);
  }
  ruleWords = std::max<std::uint32_t>(1, std::uint32_t((program.rules.size() + 63) / 64));
}

}  // namespace meldvm
