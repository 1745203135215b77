// Why a fact exists: when asked (Machine::recordDerivations), the VM notes for every fact a rule
// derives or sends the rule's source line, the node it ran at and the facts it had matched; the
// runtime of the robots notes the facts it senses. A derivation tree is then read back from the
// fact down to axioms, sensed facts and the start of the nodes (printWhy). Nothing is recorded,
// and nothing costs, unless a log is attached.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <unordered_map>
#include <vector>

#include "meldvm/program.hpp"

namespace meldvm {

// A fact as the dump prints it (`!dist(3)`: no home argument) at its node.
struct FactAt {
  NodeId node = 0;
  std::string text;
};

struct Derivation {
  enum class Kind : std::uint8_t {
    Rule,    // derived by a rule running at `at` (at != the fact's node: sent from there)
    Axiom,   // an axiom of the program (rule 0 or a node's axiom block)
    Sensed,  // asserted by the robots' runtime (neighbor, tap, ...)
  };
  Kind kind = Kind::Rule;
  std::string where;       // "file:line" of the rule or axiom; "" when the bytecode does not say
  std::string rule;        // the rule's first source line (its label)
  NodeId at = 0;           // the node the rule ran at
  std::int64_t time = -1;  // simulated ns when the host has a clock (DerivationLog::clock)
  std::vector<FactAt> premises;
};

class DerivationLog {
 public:
  // Simulated time for the records (the robots' runtime sets it); none: -1.
  std::function<std::int64_t()> clock;

  // The first derivation of a fact is kept (a later one of the same fact adds nothing).
  void record(NodeId node, std::string text, Derivation d);
  const Derivation* find(NodeId node, const std::string& text) const;
  std::size_t size() const { return records_.size(); }
  // Heap bytes the records hold (strings, vectors and the table), for the cost of recording.
  std::size_t bytesInUse() const;

 private:
  static std::string key(NodeId node, const std::string& text);
  std::unordered_map<std::string, Derivation> records_;
};

// `name(@N, args)` or `name(args)@N` as a user writes a fact (spaces do not matter, a leading `!`
// is optional):
// the node and the dump text to look up (`!name(args)` for a persistent predicate). Throws
// std::invalid_argument with what is wrong (no @node, unknown predicate ...).
FactAt parseFactSpec(const std::string& spec, const Program& program);

// One line of a derivation tree: a fact as the user writes it (`!dist(@10, 2)`), how it came
// (`rule FILE:LINE at @17, sent to @10 as a message at 1.001508 s`, `axiom FILE:LINE`, `sensed by
// the block`, ...) and the FILE:LINE it names ("" if none), at its depth (0 = the fact asked).
struct WhyLine {
  int depth = 0;
  std::string fact, how, where;
};

// The tree in pre-order, down to the axioms, the sensed facts and the nodes' start; empty when
// the log has no record of the fact. Cycles and depths past maxDepth end a branch with a note.
std::vector<WhyLine> whyTree(const DerivationLog& log, const FactAt& fact, int maxDepth = 64);

// The tree, one fact per line, indented by depth: the fact, then how it came. Returns false when
// the log has no record of the fact.
bool printWhy(std::ostream& out, const DerivationLog& log, const FactAt& fact, int maxDepth = 64);

}  // namespace meldvm
