#include "meldc/bindings.hpp"

#include <set>
#include <string>
#include <unordered_set>
#include <vector>

#include "meldc/ast/expr_vars.hpp"
#include "meldc/builtins.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

using VarSet = std::set<std::string>;

// Variables used by an expression (`let` variables are local to their body).
void uses(const Expr& e, std::vector<const Expr*>& out) {
  forEachFreeVar(e, [&](const Expr& v) { out.push_back(&v); });
}

void patternVars(const Expr& e, VarSet& bound, std::vector<const Expr*>& tests) {
  forEachPatternVar(
      e, [&](const Expr& v) { bound.insert(v.name); }, [&](const Expr& v) { tests.push_back(&v); });
}

// `X = e` with X not yet bound: an assignment of X.
const Expr* assignedVar(const Term& t, const VarSet& bound) {
  if (t.kind != TermKind::Constraint || t.cond.kind != ExprKind::Compare || t.cond.op != BinOp::Eq)
    return nullptr;
  const Expr& lhs = t.cond.args.at(0);
  if (lhs.kind == ExprKind::Var && !bound.count(lhs.name)) return &lhs;
  return nullptr;
}

class Checker {
 public:
  Checker(const Program& p, Diagnostics& diag) : diag_(diag) {
    for (const BuiltinPredicate& b : builtinPredicates()) predicates_.insert(p.symbols.find(b.name));
    for (const PredicateDecl& d : p.predicates) predicates_.insert(d.sym);
  }

  void rule(const Rule& r) {
    VarSet bound;
    bool hasSubgoal = false;
    for (const Term& t : r.body) hasSubgoal |= t.kind == TermKind::Subgoal;
    if (!hasSubgoal) {
      // A fact (axiom): a variable home argument stands for every node (§5.1).
      for (const Term& t : r.head)
        if (t.kind == TermKind::Subgoal && !t.args.empty() && t.args[0].kind == ExprKind::Var)
          bound.insert(t.args[0].name);
      // Its assignments may come in any order (they are evaluated per node before the facts).
      for (bool changed = true; changed;) {
        changed = false;
        for (const Term& t : r.head) {
          const Expr* x = assignedVar(t, bound);
          if (!x) continue;
          std::vector<const Expr*> rhs;
          uses(t.cond.args.at(1), rhs);
          bool ready = true;
          for (const Expr* v : rhs) ready &= bound.count(v->name) > 0;
          if (ready) changed = bound.insert(x->name).second || changed;
        }
      }
    }
    body(r.body, bound);
    if (r.selector) {
      if (!bound.count(r.selector->var))
        diag_.error(r.selector->loc, "selector variable '" + r.selector->var + "' is not bound by the body");
    }
    head(r.head, bound);
  }

 private:
  void unbound(const Expr& v, const char* where) {
    diag_.error(v.loc, "variable '" + v.name + "' is not bound " + where);
  }

  void requireBound(const std::vector<const Expr*>& vars, const VarSet& bound, const char* where) {
    for (const Expr* v : vars)
      if (!bound.count(v->name)) unbound(*v, where);
  }

  // A body: subgoals bind; assignments bind once their right side is bound; then every use must
  // be bound (the order of the items does not matter, §5.2).
  void body(const std::vector<Term>& items, VarSet& bound) {
    std::vector<const Expr*> tests;
    for (const Term& t : items) {
      if (t.kind != TermKind::Subgoal) continue;
      bool predicate = predicates_.count(t.sym) > 0;  // else a boolean function call
      for (const Expr& a : t.args) {
        if (predicate)
          patternVars(a, bound, tests);
        else
          uses(a, tests);
      }
    }
    std::vector<bool> assigned(items.size(), false);
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t i = 0; i < items.size(); ++i) {
        const Expr* x = assignedVar(items[i], bound);
        if (!x || assigned[i]) continue;
        std::vector<const Expr*> rhs;
        uses(items[i].cond.args.at(1), rhs);
        bool ready = true;
        for (const Expr* v : rhs) ready &= bound.count(v->name) > 0;
        if (!ready) continue;
        bound.insert(x->name);
        assigned[i] = changed = true;
      }
    }
    requireBound(tests, bound, "by the body");
    for (size_t i = 0; i < items.size(); ++i) {
      const Term& t = items[i];
      if (t.kind != TermKind::Constraint) continue;
      std::vector<const Expr*> vars;
      if (assigned[i])
        uses(t.cond.args.at(1), vars);
      else
        uses(t.cond, vars);
      requireBound(vars, bound, "by the body");
    }
  }

  void head(const std::vector<Term>& items, VarSet& bound) {
    for (const Term& t : items) headItem(t, bound);
  }

  void headItem(const Term& t, VarSet& bound) {
    switch (t.kind) {
      case TermKind::Subgoal:
        for (const Expr& a : t.args) {
          std::vector<const Expr*> vars;
          uses(a, vars);
          requireBound(vars, bound, "by the body (every head variable must be)");
        }
        break;
      case TermKind::Constraint: {
        const Expr* x = assignedVar(t, bound);
        std::vector<const Expr*> vars;
        uses(x ? t.cond.args.at(1) : t.cond, vars);
        requireBound(vars, bound, "before it is used in the head");
        if (x) bound.insert(x->name);
        break;
      }
      case TermKind::Exists: {
        VarSet inner = bound;
        for (const VarDecl& v : t.vars) inner.insert(v.name);
        head(t.head, inner);
        break;
      }
      case TermKind::Conditional: {
        std::vector<const Expr*> vars;
        uses(t.cond, vars);
        requireBound(vars, bound, "before it is used in the head");
        VarSet a = bound, b = bound;
        head(t.head, a);
        head(t.elseHead, b);
        break;
      }
      case TermKind::Comprehension: {
        VarSet inner = bound;
        body(t.body, inner);
        head(t.head, inner);
        declared(t, bound, inner, {}, "comprehension");
        break;
      }
      case TermKind::Aggregate:
        aggregate(t, bound);
        break;
    }
  }

  void aggregate(const Term& t, const VarSet& bound) {
    VarSet inner = bound;
    body(t.body, inner);
    VarSet specs;
    for (const AggSpec& s : t.specs) {
      specs.insert(s.var);
      if (s.op == AggOp::Count) {
        if (inner.count(s.var) && !bound.count(s.var))
          diag_.error(s.loc, "the 'count' variable '" + s.var + "' must not occur in the aggregate body");
      } else if (!inner.count(s.var)) {
        diag_.error(s.loc, "the aggregated variable '" + s.var + "' is not bound by the aggregate body");
      } else if (bound.count(s.var)) {
        diag_.error(s.loc, "the aggregated variable '" + s.var + "' is already bound outside the aggregate");
      }
    }
    head(t.perMatch, inner);
    for (const std::string& s : specs) inner.insert(s);
    head(t.head, inner);
    declared(t, bound, inner, specs, "aggregate");
  }

  // `Vars` of a comprehension/aggregate: exactly the variables first bound inside (§5.3.3).
  void declared(const Term& t, const VarSet& outer, const VarSet& inner, const VarSet& specs,
                const char* what) {
    VarSet listed;
    for (const VarDecl& v : t.vars) {
      listed.insert(v.name);
      if (outer.count(v.name))
        diag_.error(v.loc, "variable '" + v.name + "' is already bound outside the " + what +
                               "; list only the variables first bound inside it");
      else if (!inner.count(v.name))
        diag_.error(v.loc, "variable '" + v.name + "' is listed but not bound inside the " + what);
    }
    for (const std::string& v : inner)
      if (!outer.count(v) && !listed.count(v) && !specs.count(v))
        diag_.error(t.loc, "variable '" + v + "' is first bound inside the " + what +
                               " and must be listed among its variables");
  }

  Diagnostics& diag_;
  std::unordered_set<Symbol> predicates_;
};

}  // namespace

void checkBindings(const Program& program, Diagnostics& diag) {
  Checker checker(program, diag);
  for (const Rule& r : program.rules) checker.rule(r);
}

}  // namespace meldc
