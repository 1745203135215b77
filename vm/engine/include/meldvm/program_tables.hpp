// What the Machine looks up per predicate and per rule at every step, derived once from the
// Program: read-only while it runs.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "meldvm/program.hpp"

namespace meldvm {

struct ProgramTables {
  explicit ProgramTables(const Program& program);

  // Per predicate.
  std::vector<std::vector<std::uint32_t>> rulesOf;      // the rules with it in their body
  // A rule that a new fact of a predicate may make a candidate (Machine::factAdded, for every fact
  // stored: flat, so that the check reads no rule record): its bit in the candidate set, and the
  // distinct predicates of its body, needs[needsFrom, needsFrom + needCount). A body with thread
  // facts is checked the long way (Machine::allPresent).
  struct RuleTrigger {
    std::uint64_t bit;
    std::uint32_t word;
    std::uint32_t rule;
    std::uint32_t needsFrom;
    std::uint32_t needCount : 31;
    std::uint32_t threadFacts : 1;
  };
  std::vector<RuleTrigger> triggers;        // grouped by predicate, each group in rule order
  std::vector<std::uint32_t> triggersFrom;  // predicate p's: [triggersFrom[p], triggersFrom[p + 1])
  // With ruleWords 1: the bits of predicate p's triggers. When a node has them all already (most
  // facts stored), Machine::factAdded has nothing to look at.
  std::vector<std::uint64_t> triggerBits;
  std::vector<PredId> needs;
  std::vector<std::vector<std::uint32_t>> processesOf;  // its processes (persistent rules, §6.5)
  std::vector<std::uint8_t> queuedPersistent;           // has processes or an aggregate: derive via the queue
  std::vector<std::uint8_t> isLinear;
  std::vector<std::uint8_t> plainLinear;  // linear and not an action: sent facts wait in a buffer
  std::vector<std::uint8_t> isThreadPred;
  std::vector<std::uint32_t> arity;  // home excluded
  // The first field holding a list, or -1 (walkListsAhead in vm/engine/src/list_pipeline.hpp).
  std::vector<std::int32_t> listField;
  bool linearLists = false;  // some linear predicate has a list field
  std::uint32_t maxArity = 1;
  // Per process: the predicates its loops read at the node (with one of them empty there, the
  // process cannot fire). Thread facts live elsewhere: not listed.
  std::vector<std::vector<PredId>> processNeeds;
  // Rules whose bodies have node and thread facts (§6.12), and the flag per rule.
  std::vector<std::uint32_t> mixedRules;
  std::vector<std::uint8_t> isMixedRule;
  // Rules whose bodies have thread facts only: they run with the node that runs as host (@host).
  std::vector<std::uint32_t> threadRules;
  bool hasThreads = false;
  bool usesRandom = false;      // randint, degeneratevector or a [:random] selector
  bool createsNodes = false;    // some code runs NEWNODE (exists)
  std::uint32_t ruleWords = 1;  // 64-bit words of a node's candidate-rule bitset
  PredId justMoved = Program::kNoPred;
  // (predicate, field) pairs looked up by key: `index p/N` directives and ITER_KEY loops.
  std::vector<std::pair<PredId, std::uint32_t>> keyLookups;
};

}  // namespace meldvm
