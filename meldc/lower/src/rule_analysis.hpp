// Rule analysis (§6.4.3, §6.4.5, §6.5, §6.15): the match order of a body, which linear facts are
// kept (reuse, `$`) or updated in place, persistent-rule detection and rule merging.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "lower_context.hpp"

namespace meldc {

struct SubgoalPlan {
  const ast::Term* term = nullptr;
  const PredInfo* pred = nullptr;
  bool linear = false;
  bool thread = false;   // a thread fact (§6.12): home is a thread variable, not the host
  bool reused = false;   // `$p(...)`
  bool kept = false;     // re-derived identically by the head: that head item is dropped
  bool updated = false;  // the fact is updated in place (UPDATE) instead of consumed
  bool consumed() const { return linear && !reused && !kept && !updated; }
  // "Iterates a consumable linear subgoal" for the loops nested in it (kIterConsumableClass).
  bool consumableClass() const { return linear && !reused && !kept; }
};

struct BodyPlan {
  std::vector<SubgoalPlan> subgoals;         // in match order
  std::vector<const ast::Term*> conditions;  // constraints, assignments, boolean calls (textual)
  std::set<const ast::Term*> dropped;        // head items made redundant by reuse
  const ast::Term* updateHead = nullptr;     // head item compiled as UPDATE of subgoals[updateIndex]
  size_t updateIndex = 0;
  bool moveToBack = false;
  const ast::Selector* selector = nullptr;  // [:min X | ...] of the rule
};

// The home variable of the first body subgoal stored at a node (§6.7); throws LowerError when it is
// not a variable. Empty for a rule whose body has only thread facts: it runs at the thread node
// (§6.12) and has no host node variable.
std::string hostVariable(const Lowering& L, const ast::Rule& rule);
std::string hostConstraintVariable(const std::vector<ast::Term>& body);

// Plans a body (a rule's, a comprehension's or an aggregate's) against the head items that may
// re-derive its facts. `allowUpdate`: in-place updates apply (top-level rule bodies only).
BodyPlan planBody(const Lowering& L, const std::vector<ast::Term>& body, const std::vector<ast::Term>& head,
                  const std::string& host, const std::optional<ast::Selector>& selector, bool allowUpdate);

// §6.5: only persistent subgoals (plus kept / `$` linear ones, at least one persistent), and no
// comprehension or aggregate in the head.
bool isPersistentRule(const BodyPlan& plan, const ast::Rule& rule);

// §6.15: the key of rule merging, the multiset of body predicate names.
std::vector<ast::Symbol> bodyPredicates(const BodyPlan& plan);

// The variables written once in the whole rule (body, head, nested bodies and heads, aggregate
// results, the selector; declarations do not count): a body argument that is such a variable
// binds a value nothing reads, so it is matched as `_` (no LOAD: belief-propagation-50's rule 2
// retained and released a cold struct for every fact it tried).
std::set<std::string> singletonVariables(const ast::Rule& rule);

bool sameExpr(const ast::Expr& a, const ast::Expr& b);
bool isPredicateSubgoal(const Lowering& L, const ast::Term& t);

}  // namespace meldc
