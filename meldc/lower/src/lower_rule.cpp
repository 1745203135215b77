// User rules (§6.4.1, §6.5, §6.15): persistent rules become processes (one per occurrence of a
// persistent predicate in the body, slot 0 bound to the new fact); the others are numbered in
// program order, consecutive rules with the same body predicates merged into one.
#include "lower_rule.hpp"

#include <algorithm>

namespace meldc {

using namespace meldc::ast;
using meldvm::Opcode;

namespace {

struct Analyzed {
  const Rule* rule = nullptr;
  std::string host;
  BodyPlan plan;
  bool persistent = false;
};

// One original rule inside a numbered rule's block: its loops, head and FIRE; a test that fails
// before the first loop goes on with the next merged rule (or the final RET).
void lowerPart(Lowering& L, CodeBuilder& cb, const Analyzed& a, const BodyPlan& plan, bool prebound) {
  L.at(cb, a.rule->loc);
  RuleLowering rl(L, cb, a.host);
  rl.ignoreVariables(singletonVariables(*a.rule));
  rl.bindHost();
  CodeBuilder::Label end = cb.label();
  const auto inner = std::uint32_t(plan.subgoals.size());
  rl.match(plan, 0, end, RuleLowering::Mode::Rule, prebound, [&] { rl.head(a.rule->head, &plan, inner); });
  cb.place(end);
}

void numberedRule(Lowering& L, const std::vector<const Analyzed*>& group) {
  CodeBuilder cb;
  meldvm::Rule rule;
  std::string label;
  bool updates = false;  // an earlier part updates a fact in place
  for (const Analyzed* a : group) {
    // A merged rule tries its parts in order in one run (§6.15), except after an in-place update
    // (§6.4.5): the updated fact makes the rule a candidate again, and the node's rules are then
    // tried again from the highest priority, so later parts must not see it in this run.
    if (updates) cb.op(Opcode::RET_IF_UPDATED);
    updates = updates || a->plan.updateHead != nullptr;
    lowerPart(L, cb, *a, a->plan, false);
    if (!label.empty()) label += '\n';
    label += L.label(a->rule->loc);
    for (const SubgoalPlan& s : a->plan.subgoals)
      if (std::find(rule.bodyPredicates.begin(), rule.bodyPredicates.end(), s.pred->id) ==
          rule.bodyPredicates.end())
        rule.bodyPredicates.push_back(s.pred->id);
  }
  cb.op(Opcode::RET);
  rule.block = cb.finish(label);
  L.prog.rules.push_back(std::move(rule));
}

void processes(Lowering& L, const Analyzed& a) {
  // Occurrences in textual order; the trigger is matched first, the others keep their order.
  std::vector<const Term*> textual;
  for (const Term& t : a.rule->body)
    if (isPredicateSubgoal(L, t)) textual.push_back(&t);
  for (const Term* trigger : textual) {
    auto it = std::find_if(a.plan.subgoals.begin(), a.plan.subgoals.end(),
                           [&](const SubgoalPlan& s) { return s.term == trigger; });
    if (it == a.plan.subgoals.end() || it->linear) continue;
    BodyPlan plan = a.plan;
    const size_t at = size_t(it - a.plan.subgoals.begin());
    std::rotate(plan.subgoals.begin(), plan.subgoals.begin() + std::ptrdiff_t(at),
                plan.subgoals.begin() + std::ptrdiff_t(at) + 1);
    CodeBuilder cb;
    lowerPart(L, cb, a, plan, true);
    cb.op(Opcode::RET);
    L.prog.processes.push_back(meldvm::Process{it->pred->id, cb.finish(L.label(a.rule->loc))});
  }
}

}  // namespace

bool isAxiom(const Lowering& L, const Rule& r) {
  if (r.kind == RuleKind::Fact) return true;
  return std::none_of(r.body.begin(), r.body.end(), [&](const Term& t) { return isPredicateSubgoal(L, t); });
}

void lowerRules(Lowering& L) {
  std::vector<Analyzed> rules;
  for (const Rule& r : L.ast.rules) {
    if (isAxiom(L, r)) continue;
    try {
      Analyzed a;
      a.rule = &r;
      a.host = hostVariable(L, r);
      a.plan = planBody(L, r.body, r.head, a.host, r.selector, true);
      a.persistent = isPersistentRule(a.plan, r);
      rules.push_back(std::move(a));
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
  }
  // Numbered rules: consecutive non-persistent rules with the same body predicates are merged.
  std::vector<const Analyzed*> group;
  auto flushGroup = [&] {
    if (group.empty()) return;
    try {
      numberedRule(L, group);
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
    group.clear();
  };
  for (const Analyzed& a : rules) {
    if (a.persistent) continue;
    if (!group.empty() && bodyPredicates(group.front()->plan) != bodyPredicates(a.plan)) flushGroup();
    group.push_back(&a);
  }
  flushGroup();
  for (const Analyzed& a : rules) {
    if (!a.persistent) continue;
    try {
      processes(L, a);
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
  }
}

}  // namespace meldc
