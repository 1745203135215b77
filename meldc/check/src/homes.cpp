#include "meldc/homes.hpp"

#include <set>
#include <string>
#include <unordered_map>

#include "meldc/builtins.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

struct PredKind {
  bool route = false;
  bool thread = false;
};

class Checker {
 public:
  Checker(const Program& p, Diagnostics& diag) : diag_(diag) {
    for (const BuiltinPredicate& b : builtinPredicates()) preds_[p.symbols.find(b.name)] = {false, b.thread};
    std::unordered_map<Symbol, const TypeExpr*> aliases;
    for (const TypeAliasDecl& a : p.typeAliases) aliases[a.sym] = &a.type;
    for (const PredicateDecl& d : p.predicates) {
      const TypeExpr* home = d.fields.empty() ? nullptr : &d.fields[0].type;
      for (int guard = 0; home && home->kind == TypeKind::Named && guard < 64; ++guard) {
        auto it = aliases.find(home->sym);
        if (it == aliases.end()) break;
        home = it->second;
      }
      preds_[d.sym] = {d.route, home && home->kind == TypeKind::Thread};
    }
  }

  void rule(const Rule& r) {
    const Term* first = nullptr;
    for (const Term& t : r.body)
      if (t.kind == TermKind::Subgoal && isNodeFact(t)) {
        first = &t;
        break;
      }
    if (!first || first->args.empty() || first->args[0].kind != ExprKind::Var) return;
    const std::string& host = first->args[0].name;
    std::set<std::string> reachable{host};
    for (bool changed = true; changed;) {
      changed = false;
      for (const Term& t : r.body) {
        if (!isRoute(t) || t.args[0].kind != ExprKind::Var || !reachable.count(t.args[0].name)) continue;
        for (size_t i = 1; i < t.args.size(); ++i)
          if (t.args[i].kind == ExprKind::Var && reachable.insert(t.args[i].name).second) changed = true;
      }
    }
    for (const Term& t : r.body) {
      if (!isNodeFact(t) || t.args.empty() || t.args[0].kind != ExprKind::Var) continue;
      if (reachable.count(t.args[0].name)) continue;
      diag_.error(t.args[0].loc, "bad home argument: '" + t.name + "' is at '" + t.args[0].name +
                                     "', which is neither the host '" + host +
                                     "' of the rule nor reached from it through a route fact");
    }
  }

 private:
  const PredKind* kind(const Term& t) const {
    auto it = preds_.find(t.sym);
    return it == preds_.end() ? nullptr : &it->second;
  }
  bool isNodeFact(const Term& t) const {
    const PredKind* k = kind(t);
    return t.kind == TermKind::Subgoal && k && !k->thread;
  }
  bool isRoute(const Term& t) const {
    const PredKind* k = kind(t);
    return t.kind == TermKind::Subgoal && k && k->route && !t.args.empty();
  }

  Diagnostics& diag_;
  std::unordered_map<Symbol, PredKind> preds_;
};

}  // namespace

void checkHomes(const Program& program, Diagnostics& diag) {
  Checker checker(program, diag);
  for (const Rule& r : program.rules) checker.rule(r);
}

}  // namespace meldc
