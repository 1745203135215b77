#include "meldc/names.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "meldc/ast_dump.hpp"
#include "meldc/builtins.hpp"
#include "meldc/case_folding.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string plural(size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

struct PredInfo {
  std::string name;  // spelling of the declaration
  size_t arity = 0;
  bool linear = false;
  bool instruction = false;
  bool action = false;
  const PredicateDecl* decl = nullptr;  // null for built-ins
};

struct FunInfo {
  std::string name;
  size_t arity = 0;
  SourceLoc loc;  // invalid for built-ins
};

class Resolver {
 public:
  Resolver(const Program& p, Diagnostics& diag) : p_(p), diag_(diag) {}

  void run() {
    declareTypes();
    declarePredicates();
    declareFunctions();
    checkDirectives();
    for (const ConstDecl& c : p_.consts) expr(c.value, nullptr);
    for (const FunDecl& f : p_.funs) {
      std::set<std::string> scope;
      for (const FunParam& param : f.params) {
        checkType(param.type);
        scope.insert(param.name);
      }
      checkType(f.result);
      expr(f.body, &scope);
    }
    for (const Rule& r : p_.rules) rule(r);
  }

 private:
  // --- declarations ------------------------------------------------------------------------

  void duplicate(SourceLoc loc, const std::string& what, const std::string& name, SourceLoc previous) {
    diag_.error(loc, what + " '" + name + "' is declared more than once");
    if (previous.valid()) diag_.note(previous, "previous declaration is here");
  }

  void declareTypes() {
    for (const NodeTypeDecl& n : p_.nodeTypes) {
      if (auto it = typeNames_.find(n.sym); it != typeNames_.end())
        duplicate(n.loc, "type", n.name, it->second);
      else {
        typeNames_[n.sym] = n.loc;
        nodeTypes_.insert(n.sym);
      }
    }
    for (const TypeAliasDecl& a : p_.typeAliases) {
      if (auto it = typeNames_.find(a.sym); it != typeNames_.end())
        duplicate(a.loc, "type", a.name, it->second);
      else {
        typeNames_[a.sym] = a.loc;
        aliases_[a.sym] = &a.type;
      }
    }
    for (const TypeAliasDecl& a : p_.typeAliases) checkType(a.type);
  }

  void checkType(const TypeExpr& t) {
    if (t.kind == TypeKind::Named && !typeNames_.count(t.sym))
      diag_.error(t.loc, "unknown type '" + t.name + "'");
    for (const TypeExpr& a : t.args) checkType(a);
  }

  // Follows aliases; returns the final type (a Named type left is a node subtype or unknown).
  const TypeExpr& resolveAlias(const TypeExpr& t) const {
    const TypeExpr* cur = &t;
    for (int guard = 0; cur->kind == TypeKind::Named && guard < 64; ++guard) {
      auto it = aliases_.find(cur->sym);
      if (it == aliases_.end()) break;
      cur = it->second;
    }
    return *cur;
  }

  bool isNumeric(const TypeExpr& t) const {
    const TypeExpr& r = resolveAlias(t);
    return r.kind == TypeKind::Int || r.kind == TypeKind::Float;
  }

  void declarePredicates() {
    for (const BuiltinPredicate& b : builtinPredicates()) {
      PredInfo info;
      info.name = std::string(b.name);
      info.arity = static_cast<size_t>(b.arity());
      info.linear = b.kind == BuiltinPredKind::Linear;
      info.instruction = b.kind == BuiltinPredKind::Instruction;
      info.action = b.action;
      preds_[p_.symbols.find(b.name)] = info;
    }
    for (const PredicateDecl& d : p_.predicates) {
      auto it = preds_.find(d.sym);
      if (it != preds_.end() && it->second.decl) {
        duplicate(d.nameLoc, "predicate", d.name, it->second.decl->nameLoc);
        continue;
      }
      // A declaration may redefine a built-in (robot include files declare their own actions).
      PredInfo info;
      info.name = d.name;
      info.arity = d.fields.size();
      info.linear = d.linear;
      info.action = d.action;
      info.decl = &d;
      preds_[d.sym] = info;
      checkPredicate(d);
    }
  }

  void checkPredicate(const PredicateDecl& d) {
    if (d.fields.empty()) {
      diag_.error(d.nameLoc, "predicate '" + d.name + "' needs at least one argument, its home node");
      return;
    }
    for (const FieldDecl& f : d.fields) checkType(f.type);
    const TypeExpr& home = resolveAlias(d.fields[0].type);
    bool homeOk = home.kind == TypeKind::Node || home.kind == TypeKind::Thread ||
                  (home.kind == TypeKind::Named && nodeTypes_.count(home.sym));
    if (!homeOk && (home.kind != TypeKind::Named || typeNames_.count(home.sym)))
      diag_.error(d.fields[0].loc, "the first argument of '" + d.name +
                                       "' is its home and must be a node, a node type or a thread, not '" +
                                       toString(d.fields[0].type) + "'");
    int aggregates = 0;
    for (size_t i = 0; i < d.fields.size(); ++i) {
      const FieldDecl& f = d.fields[i];
      if (f.agg == FieldAgg::None) continue;
      if (++aggregates == 2)
        diag_.error(f.loc, "predicate '" + d.name + "' has more than one aggregate field");
      if (i == 0) {
        diag_.error(f.loc, "the home argument of '" + d.name + "' cannot be aggregated");
        continue;
      }
      const TypeExpr& t = resolveAlias(f.type);
      if ((f.agg == FieldAgg::Min || f.agg == FieldAgg::Max) && !isNumeric(f.type))
        diag_.error(f.type.loc, std::string(f.agg == FieldAgg::Min ? "min" : "max") +
                                    " aggregates int or float fields, not '" + toString(f.type) + "'");
      if (f.agg == FieldAgg::Sum && !isNumeric(f.type) &&
          !(t.kind == TypeKind::List && !t.args.empty() && resolveAlias(t.args[0]).kind == TypeKind::Float))
        diag_.error(f.type.loc,
                    "sum aggregates int, float or list float fields, not '" + toString(f.type) + "'");
    }
  }

  void declareFunctions() {
    for (const BuiltinFunction& b : builtinFunctions())
      builtinFuns_[p_.symbols.find(b.name)] = FunInfo{std::string(b.name), static_cast<size_t>(b.arity), {}};
    for (const ExternDecl& e : p_.externs) {
      checkType(e.result);
      for (const FieldDecl& f : e.params) checkType(f.type);
      if (auto it = externs_.find(e.sym); it != externs_.end())
        duplicate(e.loc, "extern", e.name, it->second.loc);
      else
        externs_[e.sym] = FunInfo{e.name, e.params.size(), e.loc};
    }
    for (const ConstDecl& c : p_.consts) {
      if (auto it = consts_.find(c.sym); it != consts_.end())
        duplicate(c.loc, "constant", c.name, it->second);
      else
        consts_[c.sym] = c.loc;
    }
    for (const FunDecl& f : p_.funs) {
      if (auto it = funs_.find(f.sym); it != funs_.end())
        duplicate(f.loc, "function", f.name, it->second.loc);
      else
        funs_[f.sym] = FunInfo{f.name, f.params.size(), f.loc};
    }
  }

  const PredInfo* predicate(Symbol name) const {
    auto it = preds_.find(name);
    return it == preds_.end() ? nullptr : &it->second;
  }

  // User functions first, then built-in externals, then declared externs (§5.5).
  const FunInfo* function(Symbol name) const {
    if (auto it = funs_.find(name); it != funs_.end()) return &it->second;
    if (auto it = builtinFuns_.find(name); it != builtinFuns_.end()) return &it->second;
    if (auto it = externs_.find(name); it != externs_.end()) return &it->second;
    return nullptr;
  }

  // The closest predicate name within two edits; on a tie the first in alphabetical order.
  std::string suggestion(const std::string& name) const {
    const std::string key = lower(name);
    const std::string* bestKey = nullptr;
    std::string best;
    size_t bestDistance = 3;
    for (const auto& [sym, info] : preds_) {
      const std::string& k = p_.symbols.text(sym);
      if (k.empty() || k[0] == '_') continue;
      size_t d = editDistance(key, k);
      if (d >= key.size()) continue;
      if (d < bestDistance || (d == bestDistance && bestKey && k < *bestKey)) {
        bestDistance = d;
        bestKey = &k;
        best = info.name;
      }
    }
    return best.empty() ? "" : "; did you mean '" + best + "'?";
  }

  void checkDirectives() {
    for (const Directive& d : p_.directives) {
      auto requirePredicate = [&](Symbol sym, const std::string& name, SourceLoc loc,
                                  const char* what) -> const PredInfo* {
        const PredInfo* info = predicate(sym);
        if (!info)
          diag_.error(loc, "unknown predicate '" + name + "' in " + what + " directive" + suggestion(name));
        return info;
      };
      switch (d.kind) {
        case DirectiveKind::Index:
          if (const PredInfo* info = requirePredicate(d.sym, d.name, d.nameLoc, "index")) {
            if (d.position < 1 || static_cast<size_t>(d.position) > info->arity)
              diag_.error(d.nameLoc, "index field " + std::to_string(d.position) + " does not exist: '" +
                                         info->name + "' has " + plural(info->arity, "argument") +
                                         " (fields count from 1, the home)");
          }
          break;
        case DirectiveKind::Compact:
          requirePredicate(d.sym, d.name, d.nameLoc, "compact");
          break;
        case DirectiveKind::Priority:
          if (d.priority == PriorityKind::Lower || d.priority == PriorityKind::Higher) {
            requirePredicate(d.sym, d.name, d.nameLoc, "priority");
            requirePredicate(d.otherSym, d.other, d.otherLoc, "priority");
          }
          break;
        default:
          break;
      }
    }
  }

  // --- rules -------------------------------------------------------------------------------

  void rule(const Rule& r) {
    for (const Term& t : r.body) term(t, /*inBody=*/true, r.kind == RuleKind::Fact);
    for (const Term& t : r.head) term(t, /*inBody=*/false, r.kind == RuleKind::Fact);
  }

  void terms(const std::vector<Term>& ts, bool inBody, bool fact) {
    for (const Term& t : ts) term(t, inBody, fact);
  }

  void term(const Term& t, bool inBody, bool fact) {
    switch (t.kind) {
      case TermKind::Subgoal:
        subgoal(t, inBody, fact);
        break;
      case TermKind::Constraint:
        expr(t.cond, nullptr);
        break;
      case TermKind::Exists:
        terms(t.head, false, fact);
        break;
      case TermKind::Comprehension:
        terms(t.body, true, fact);
        terms(t.head, false, fact);
        break;
      case TermKind::Aggregate:
        for (const AggSpec& s : t.specs) {
          if (s.op != AggOp::Custom) continue;
          const FunInfo* f = function(s.functionSym);
          if (!f)
            diag_.error(s.loc, "unknown function '" + s.function + "' in custom aggregate");
          else if (f->arity != 2)
            diag_.error(s.loc, "custom aggregate function '" + f->name +
                                   "' must take 2 arguments, it takes " + std::to_string(f->arity));
          expr(s.start, nullptr);
        }
        terms(t.body, true, fact);
        terms(t.perMatch, false, fact);
        terms(t.head, false, fact);
        break;
      case TermKind::Conditional:
        expr(t.cond, nullptr);
        terms(t.head, false, fact);
        terms(t.elseHead, false, fact);
        break;
    }
  }

  void subgoal(const Term& t, bool inBody, bool fact) {
    for (const Expr& a : t.args) expr(a, nullptr);
    const PredInfo* info = predicate(t.sym);
    if (!info) {
      // In a body, `f(X, Y)` may be a boolean-valued function call (a constraint).
      if (inBody && t.mark == Mark::None && !t.delayMs) {
        if (const FunInfo* f = function(t.sym)) {
          checkCall(t.nameLoc, *f, t.args.size());
          return;
        }
      }
      diag_.error(t.nameLoc, "unknown predicate '" + t.name + "'" + suggestion(t.name));
      return;
    }
    if (t.args.size() != info->arity) {
      diag_.error(t.nameLoc, "predicate '" + info->name + "' takes " + plural(info->arity, "argument") +
                                 ", " + std::to_string(t.args.size()) + " given");
      if (info->decl) diag_.note(info->decl->nameLoc, "'" + info->name + "' is declared here");
    }
    if (t.delayMs && inBody)
      diag_.error(t.loc, "a delay ('@+...') is only allowed on facts derived in a head");
    if (inBody && info->instruction) {
      diag_.error(t.nameLoc, "'" + info->name + "' is an instruction; it can only be used in a head");
      return;
    }
    if (inBody && info->action) {
      diag_.error(t.nameLoc, "'" + info->name +
                                 "' is an action: it is run when derived, never stored, so it can "
                                 "only stand in a head (§7.2)");
      return;
    }
    if (fact && p_.symbols.text(t.sym) == "schedule-next")
      diag_.error(t.nameLoc, "'schedule-next' cannot be used in a fact (axiom)");
    if (info->instruction) return;
    if (!inBody && t.mark == Mark::Reuse) {
      diag_.error(t.loc, "'$' is not allowed in a head; it only marks body facts that are kept");
      return;
    }
    if (info->linear) {
      if (t.mark == Mark::Persistent)
        diag_.error(t.loc, "'" + info->name + "' is linear; '!' is only for persistent predicates");
      return;
    }
    // Persistent predicate.
    if (t.mark == Mark::Linear)
      diag_.error(t.loc, "'" + info->name + "' is persistent; '?' is only for linear predicates");
    else if (t.mark == Mark::Reuse)
      diag_.error(t.loc, "'" + info->name + "' is persistent; '$' is only for linear predicates");
    else if (t.mark == Mark::None && !fact)  // facts like `edge(@1, @2).` are common: no warning there
      diag_.warning(t.loc,
                    "persistent predicate '" + info->name + "' should be written '!" + t.name + "(...)'");
  }

  void checkCall(SourceLoc loc, const FunInfo& f, size_t given) {
    if (f.arity != given)
      diag_.error(loc, "function '" + f.name + "' takes " + plural(f.arity, "argument") + ", " +
                           std::to_string(given) + " given");
  }

  // Checks the names in an expression; `scope` (function bodies) lists the variables in scope.
  void expr(const Expr& e, std::set<std::string>* scope) {
    switch (e.kind) {
      case ExprKind::Const:
        if (!consts_.count(e.sym)) {
          std::string hint;
          if (e.name.find('-') != std::string::npos)
            hint = "; '-' is part of names, write '" + e.name.substr(0, e.name.find('-')) + " - " +
                   e.name.substr(e.name.find('-') + 1) + "' to subtract";
          diag_.error(e.loc, "unknown constant '" + e.name + "'" + hint);
        }
        return;
      case ExprKind::Call: {
        const FunInfo* f = function(e.sym);
        if (!f) {
          std::string hint = predicate(e.sym) ? "; '" + e.name + "' is a predicate, not a function" : "";
          diag_.error(e.loc, "unknown function '" + e.name + "'" + hint);
        } else {
          checkCall(e.loc, *f, e.args.size());
        }
        break;
      }
      case ExprKind::Var:
        if (scope && !scope->count(e.name)) diag_.error(e.loc, "unknown variable '" + e.name + "'");
        return;
      case ExprKind::Let:
        if (scope) {
          expr(e.args.at(0), scope);
          bool added = scope->insert(e.name).second;
          expr(e.args.at(1), scope);
          if (added) scope->erase(e.name);
          return;
        }
        break;
      default:
        break;
    }
    for (const Expr& a : e.args) expr(a, scope);
  }

  const Program& p_;
  Diagnostics& diag_;
  std::unordered_map<Symbol, SourceLoc> typeNames_;
  std::unordered_set<Symbol> nodeTypes_;
  std::unordered_map<Symbol, const TypeExpr*> aliases_;
  std::unordered_map<Symbol, PredInfo> preds_;
  std::unordered_map<Symbol, FunInfo> funs_, builtinFuns_, externs_;
  std::unordered_map<Symbol, SourceLoc> consts_;
};

}  // namespace

void resolveNames(const Program& program, Diagnostics& diag) { Resolver(program, diag).run(); }

}  // namespace meldc
