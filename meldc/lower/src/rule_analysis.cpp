#include "rule_analysis.hpp"

#include <algorithm>
#include <map>

namespace meldc {

using namespace meldc::ast;

namespace {

bool mentions(const Expr& e, const std::string& var) {
  if (e.kind == ExprKind::Var && e.name == var) return true;
  for (const Expr& a : e.args)
    if (mentions(a, var)) return true;
  return false;
}

bool hasAggregateOrComprehension(const std::vector<Term>& head) {
  for (const Term& t : head) {
    if (t.kind == TermKind::Comprehension || t.kind == TermKind::Aggregate) return true;
    if (hasAggregateOrComprehension(t.head) || hasAggregateOrComprehension(t.elseHead)) return true;
  }
  return false;
}

// A head item that derives a fact of `pred` at the node (or thread) held by variable `home`
// without delay.
bool derivesAt(const Term& h, Symbol pred, const std::string& home) {
  return h.kind == TermKind::Subgoal && h.sym == pred && !h.delayMs && !h.args.empty() &&
         h.args[0].kind == ExprKind::Var && h.args[0].name == home;
}

}  // namespace

namespace {

using VariableCounts = std::map<std::string, int>;

void countVariables(const Expr& e, VariableCounts& n) {
  if (e.kind == ExprKind::Var || e.kind == ExprKind::Let) ++n[e.name];
  for (const Expr& a : e.args) countVariables(a, n);
}

void countVariables(const std::vector<Term>& terms, VariableCounts& n) {
  for (const Term& t : terms) {
    for (const Expr& a : t.args) countVariables(a, n);
    countVariables(t.cond, n);
    // (A comprehension's or an aggregate's declared variables are not counted: a declaration
    // reads nothing, and `{B, W | !edge(A, B, W) | ...}` need not load W.)
    for (const AggSpec& s : t.specs) {
      ++n[s.var];
      countVariables(s.start, n);
    }
    countVariables(t.body, n);
    countVariables(t.perMatch, n);
    countVariables(t.head, n);
    countVariables(t.elseHead, n);
  }
}

}  // namespace

std::set<std::string> singletonVariables(const Rule& rule) {
  VariableCounts n;
  countVariables(rule.body, n);
  countVariables(rule.head, n);
  if (rule.selector) ++n[rule.selector->var];
  std::set<std::string> once;
  for (const auto& [name, count] : n)
    if (count == 1) once.insert(name);
  return once;
}

bool sameExpr(const Expr& a, const Expr& b) {
  if (a.kind != b.kind || a.args.size() != b.args.size() || a.hasTail != b.hasTail) return false;
  switch (a.kind) {
    case ExprKind::Anon:
      return false;  // `_` matches anything: never the same value as a head expression
    case ExprKind::Var:
    case ExprKind::String:
      if (a.name != b.name) return false;
      break;
    case ExprKind::Const:
    case ExprKind::Call:
      if (a.sym != b.sym) return false;
      break;
    case ExprKind::Let:
      if (a.name != b.name) return false;
      break;
    case ExprKind::Int:
    case ExprKind::Node:
    case ExprKind::Arg:
      if (a.intValue != b.intValue) return false;
      break;
    case ExprKind::Float:
      if (a.floatValue != b.floatValue) return false;
      break;
    case ExprKind::Bool:
      if (a.boolValue != b.boolValue) return false;
      break;
    case ExprKind::Binary:
    case ExprKind::Compare:
      if (a.op != b.op) return false;
      break;
    default:
      break;
  }
  for (size_t i = 0; i < a.args.size(); ++i)
    if (!sameExpr(a.args[i], b.args[i])) return false;
  return true;
}

bool isPredicateSubgoal(const Lowering& L, const Term& t) {
  if (t.kind != TermKind::Subgoal) return false;
  const PredInfo* p = L.pred(t.sym);
  return p && p->id != meldvm::Program::kNoPred;
}

std::string hostVariable(const Lowering& L, const Rule& rule) {
  for (const Term& t : rule.body) {
    if (!isPredicateSubgoal(L, t) || L.desc(*L.pred(t.sym)).thread) continue;
    if (t.args.empty() || t.args[0].kind != ExprKind::Var)
      throw LowerError(t.loc, "the home of a body fact must be a variable, the rule's host (§5.2)");
    return t.args[0].name;
  }
  for (const Term& t : rule.body)
    if (isPredicateSubgoal(L, t)) return hostConstraintVariable(rule.body);  // only thread facts
  throw LowerError(rule.loc, "internal error: rule without body facts");
}

// A rule over thread facts only runs while a node runs (§6.12); a constraint `V = @host` names
// that node, and facts at V (in a comprehension or aggregate) are the running node's, as the
// established compiler has it.
std::string hostConstraintVariable(const std::vector<Term>& body) {
  for (const Term& t : body) {
    if (t.kind != TermKind::Constraint || t.cond.kind != ExprKind::Compare || t.cond.op != BinOp::Eq)
      continue;
    const Expr& a = t.cond.args.at(0);
    const Expr& b = t.cond.args.at(1);
    if (a.kind == ExprKind::Var && b.kind == ExprKind::Host) return a.name;
    if (b.kind == ExprKind::Var && a.kind == ExprKind::Host) return b.name;
  }
  return "";
}

BodyPlan planBody(const Lowering& L, const std::vector<Term>& body, const std::vector<Term>& head,
                  const std::string& host, const std::optional<Selector>& selector, bool allowUpdate) {
  BodyPlan plan;
  plan.selector = selector ? &*selector : nullptr;
  std::vector<SubgoalPlan> textual;
  for (const Term& t : body) {
    if (!isPredicateSubgoal(L, t)) {
      if (t.kind == TermKind::Subgoal || t.kind == TermKind::Constraint)
        plan.conditions.push_back(&t);
      else
        throw LowerError(t.loc, "a rule body holds facts, constraints and assignments only (§5.2)");
      continue;
    }
    SubgoalPlan s;
    s.term = &t;
    s.pred = L.pred(t.sym);
    s.linear = L.desc(*s.pred).linear;
    s.thread = L.desc(*s.pred).thread;
    s.reused = t.mark == Mark::Reuse;
    // A thread fact may name any thread variable (it stands for the running thread and is bound
    // or checked with THREAD); node facts must be at the host.
    const ExprKind home = t.args.empty() ? ExprKind::Anon : t.args[0].kind;
    const bool homeOk = s.thread ? !t.args.empty() && (home == ExprKind::Var || home == ExprKind::Anon)
                                 : home == ExprKind::Var && t.args[0].name == host;
    if (!homeOk)
      throw LowerError(
          t.args.empty() ? t.loc : t.args[0].loc,
          s.thread
              ? "the home of a thread fact in a body must be a thread variable (§6.12)"
              : "'" + t.name + "' is at another node than the rule's host and no route leads there (§6.7)");
    textual.push_back(s);
  }

  // Reuse (§6.4.5): a linear subgoal re-derived identically at its home (the host, or the same
  // thread variable for a thread fact) is not consumed.
  std::vector<bool> used(head.size(), false);
  for (SubgoalPlan& s : textual) {
    if (!s.linear || s.reused || s.term->args[0].kind != ExprKind::Var) continue;
    const Symbol name = s.term->sym;
    for (size_t h = 0; h < head.size(); ++h) {
      if (used[h] || !derivesAt(head[h], name, s.term->args[0].name) ||
          head[h].args.size() != s.term->args.size())
        continue;
      bool same = true;
      for (size_t a = 1; a < head[h].args.size() && same; ++a)
        same = sameExpr(head[h].args[a], s.term->args[a]);
      if (!same) continue;
      used[h] = true;
      s.kept = true;
      plan.dropped.insert(&head[h]);
      break;
    }
  }

  // Match order (§6.4.3): selector subgoals first, subgoals of indexed predicates last.
  std::set<meldvm::PredId> indexed;
  for (const meldvm::IndexRequest& r : L.prog.indexes) indexed.insert(r.predicate);
  auto rank = [&](const SubgoalPlan& s) {
    if (selector) {
      for (size_t a = 1; a < s.term->args.size(); ++a)
        if (mentions(s.term->args[a], selector->var)) return 0;
    }
    return indexed.count(s.pred->id) ? 2 : 1;
  };
  plan.subgoals = textual;
  std::stable_sort(plan.subgoals.begin(), plan.subgoals.end(),
                   [&](const SubgoalPlan& a, const SubgoalPlan& b) { return rank(a) < rank(b); });

  // In-place update (§6.4.5), only for an unconditional head item outside comprehensions.
  if (!allowUpdate) return plan;
  for (size_t h = 0; h < head.size() && !plan.updateHead; ++h) {
    if (used[h] || head[h].kind != TermKind::Subgoal) continue;
    const Symbol name = head[h].sym;
    // Not for thread facts: UPDATE rewrites a fact of the host's store.
    if (!derivesAt(head[h], name, host)) continue;
    std::vector<size_t> consumed;
    for (size_t i = 0; i < plan.subgoals.size(); ++i)
      if (plan.subgoals[i].consumed() && plan.subgoals[i].term->sym == name) consumed.push_back(i);
    if (consumed.empty()) continue;
    plan.updateHead = &head[h];
    plan.updateIndex = consumed.front();  // the outermost such loop
    plan.subgoals[consumed.front()].updated = true;
    plan.moveToBack = consumed.size() == 1 && consumed.front() != 0;
  }
  return plan;
}

bool isPersistentRule(const BodyPlan& plan, const Rule& rule) {
  bool persistent = false;
  for (const SubgoalPlan& s : plan.subgoals) {
    if (s.linear && !s.reused && !s.kept) return false;
    persistent |= !s.linear;
  }
  return persistent && !hasAggregateOrComprehension(rule.head);
}

std::vector<Symbol> bodyPredicates(const BodyPlan& plan) {
  std::vector<Symbol> names;
  for (const SubgoalPlan& s : plan.subgoals) names.push_back(s.term->sym);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace meldc
