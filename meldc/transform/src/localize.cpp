#include "meldc/localize.hpp"

#include <algorithm>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "meldc/ast/expr_vars.hpp"
#include "meldc/builtins.hpp"
#include "meldc/types.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

using VarSet = std::set<std::string>;
using VarList = std::vector<std::string>;
using VarTypes = std::map<std::string, TypeExpr>;

// Variables of an expression in textual order, repeats included (`let` variables are local).
void exprVars(const Expr& e, VarList& out) {
  forEachFreeVar(e, [&](const Expr& v) { out.push_back(v.name); });
}

// Calls `f` on every expression of a term, nested constructs included.
template <class F>
void eachExpr(const Term& t, const F& f) {
  for (const Expr& a : t.args) f(a);
  if (t.kind == TermKind::Constraint || t.kind == TermKind::Conditional) f(t.cond);
  for (const AggSpec& s : t.specs) f(s.start);
  for (const std::vector<Term>* ts : {&t.body, &t.perMatch, &t.head, &t.elseHead})
    for (const Term& u : *ts) eachExpr(u, f);
}

// Every variable a term mentions (over-approximates what the rest of a rule needs from the
// neighbour: a variable of a nested construct may shadow one, which only passes one more value).
void termVars(const Term& t, VarList& out) {
  eachExpr(t, [&](const Expr& e) { exprVars(e, out); });
}

void patternVars(const Expr& e, VarSet& bound, VarList& tests) {
  forEachPatternVar(
      e, [&](const Expr& v) { bound.insert(v.name); }, [&](const Expr& v) { tests.push_back(v.name); });
}

// The inferred type of each variable of an expression (the first occurrence the checker typed).
void varTypes(const Expr& e, const Typing& typing, std::map<std::string, TypeExpr>& out) {
  if (e.kind == ExprKind::Var && !out.count(e.name))
    if (const TypeExpr* t = typing.of(e)) out[e.name] = *t;
  for (const Expr& a : e.args) varTypes(a, typing, out);
}

bool allIn(const VarList& vars, const VarSet& set) {
  return std::all_of(vars.begin(), vars.end(), [&](const std::string& v) { return set.count(v) > 0; });
}

Expr var(SourceLoc loc, const std::string& name) {
  Expr e;
  e.kind = ExprKind::Var;
  e.loc = loc;
  e.name = name;
  return e;
}

struct PredInfo {
  const PredicateDecl* decl = nullptr;  // null for built-ins
  bool linear = false;
  bool thread = false;
  bool routeEdge = false;  // a route whose second argument is a node: it can lead to a neighbour
};

constexpr int kHost = -1;
constexpr int kUndecided = -2;  // a condition (constraint, assignment, boolean function call)

class Localizer {
 public:
  Localizer(Program& p, Diagnostics& diag) : p_(p), diag_(diag) {
    for (const BuiltinPredicate& b : builtinPredicates())
      preds_[p.symbols.find(b.name)] = {nullptr, b.kind == BuiltinPredKind::Linear, b.thread, false};
    for (const TypeAliasDecl& a : p.typeAliases) aliases_[a.sym] = &a.type;
    for (const PredicateDecl& d : p.predicates) {
      PredInfo info{&d, d.linear, false, false};
      if (!d.fields.empty()) info.thread = resolve(d.fields[0].type).kind == TypeKind::Thread;
      if (d.route && d.fields.size() >= 2) {
        TypeKind k = resolve(d.fields[1].type).kind;
        info.routeEdge = k == TypeKind::Node || k == TypeKind::Named;  // Named: a node subtype
      }
      preds_[d.sym] = info;
    }
  }

  void run() {
    std::vector<Rule> rules;
    rules.reserve(p_.rules.size());
    for (const Rule& r : p_.rules) rules.push_back(rule(r));
    if (generatedRules_.empty()) return;  // nothing spans nodes: leave the program untouched
    p_.rules.clear();
    for (Rule& r : generatedRules_) p_.rules.push_back(std::move(r));
    for (GroundFact& f : p_.groundFacts.facts) f.position += static_cast<uint32_t>(generatedRules_.size());
    for (Rule& r : rules) p_.rules.push_back(std::move(r));
    for (PredicateDecl& d : helpers_) p_.predicates.push_back(std::move(d));
    for (PredicateDecl& d : inverses_) p_.predicates.push_back(std::move(d));
  }

 private:
  struct Edge {
    size_t route = 0;  // index of the route subgoal in the body
    std::string neighbour;
    VarSet bound;  // variables bound at the neighbour
  };

  const TypeExpr& resolve(const TypeExpr& t) const {
    const TypeExpr* r = &t;
    for (int guard = 0; r->kind == TypeKind::Named && guard < 64; ++guard) {
      auto it = aliases_.find(r->sym);
      if (it == aliases_.end()) break;
      r = it->second;
    }
    return *r;
  }

  const PredInfo* info(const Term& t) const {
    if (t.kind != TermKind::Subgoal) return nullptr;
    auto it = preds_.find(t.sym);
    return it == preds_.end() ? nullptr : &it->second;
  }
  // A subgoal of a predicate stored at a node (not a thread fact, not a boolean function call).
  bool nodeFact(const Term& t) const {
    const PredInfo* i = info(t);
    return i && !i->thread;
  }
  static const std::string* homeVar(const Term& t) {
    return !t.args.empty() && t.args[0].kind == ExprKind::Var ? &t.args[0].name : nullptr;
  }
  // The node variable a route subgoal leads to from its home variable (null for anything else).
  const std::string* routeTarget(const Term& t) const {
    const PredInfo* pi = info(t);
    if (!pi || !pi->routeEdge || !homeVar(t) || t.args.size() < 2 || t.args[1].kind != ExprKind::Var)
      return nullptr;
    return &t.args[1].name;
  }

  // `inherited`: the variable types of the rule this one was split from (its expressions are
  // copies the type checker never saw).
  // A generated subgoal; its name joins the program's symbols.
  Term subgoal(SourceLoc loc, Mark mark, const std::string& name, std::vector<Expr> args) {
    Term t;
    t.kind = TermKind::Subgoal;
    t.loc = t.nameLoc = loc;
    t.mark = mark;
    t.name = name;
    t.sym = p_.symbols.intern(name);
    t.args = std::move(args);
    return t;
  }

  Rule rule(const Rule& r, const VarTypes* inherited = nullptr) {
    if (r.kind == RuleKind::Fact) return r;
    const std::string* host = nullptr;
    for (const Term& t : r.body)
      if (nodeFact(t)) {
        host = homeVar(t);
        break;
      }
    if (!host) return r;

    // Candidate edges: route subgoals at the host, one per neighbour variable (the first wins).
    std::vector<Edge> candidates;
    for (size_t i = 0; i < r.body.size(); ++i) {
      const std::string* to = routeTarget(r.body[i]);
      if (!to || *homeVar(r.body[i]) != *host || *to == *host) continue;
      bool known = std::any_of(candidates.begin(), candidates.end(),
                               [&](const Edge& e) { return e.neighbour == *to; });
      if (!known) candidates.push_back(Edge{i, *to, {}});
    }
    // Nodes further away (§6.7: reachable through route subgoals) belong to the edge of the
    // neighbour they are reached through; that part of the body is localized again from there.
    std::map<std::string, size_t> through;  // node variable -> candidate edge
    for (size_t c = 0; c < candidates.size(); ++c) through.emplace(candidates[c].neighbour, c);
    for (bool grew = true; grew;) {
      grew = false;
      for (const Term& t : r.body) {
        const std::string* to = routeTarget(t);
        if (!to || *to == *host || through.count(*to)) continue;
        if (auto from = through.find(*homeVar(t)); from != through.end()) {
          through.emplace(*to, from->second);
          grew = true;
        }
      }
    }

    // Sides of the body items: host, an edge (its neighbour), or undecided (conditions).
    std::vector<int> candidateOf(r.body.size(), kHost);
    std::vector<bool> used(candidates.size(), false);
    for (size_t i = 0; i < r.body.size(); ++i) {
      const Term& t = r.body[i];
      if (!info(t)) candidateOf[i] = kUndecided;
      const std::string* h = nodeFact(t) ? homeVar(t) : nullptr;
      if (!h || *h == *host) continue;
      auto it = through.find(*h);
      if (it == through.end()) {
        unreachable(t, *host);
        return r;
      }
      candidateOf[i] = static_cast<int>(it->second);
      used[it->second] = true;
    }
    std::vector<Edge> edges;
    std::vector<int> edgeOf(candidates.size(), kHost);  // a route without facts beyond stays
    for (size_t c = 0; c < candidates.size(); ++c) {
      if (!used[c]) continue;
      edgeOf[c] = static_cast<int>(edges.size());
      candidateOf[candidates[c].route] = static_cast<int>(c);
      edges.push_back(candidates[c]);
    }
    if (edges.empty()) return r;
    std::vector<int> side(r.body.size());
    for (size_t i = 0; i < r.body.size(); ++i)
      side[i] = candidateOf[i] < 0 ? candidateOf[i] : edgeOf[static_cast<size_t>(candidateOf[i])];

    // What each side binds; a neighbour subgoal may not test variables bound elsewhere.
    VarSet hostBound;
    VarList tests;
    for (size_t i = 0; i < r.body.size(); ++i)
      if (side[i] == kHost)
        for (const Expr& a : r.body[i].args) patternVars(a, hostBound, tests);
    for (size_t e = 0; e < edges.size(); ++e) {
      VarList edgeTests;
      for (size_t i = 0; i < r.body.size(); ++i)
        if (side[i] == static_cast<int>(e))
          for (const Expr& a : r.body[i].args) patternVars(a, edges[e].bound, edgeTests);
      for (const std::string& v : edgeTests)
        if (!edges[e].bound.count(v)) {
          diag_.error(r.loc, "cannot localize this rule: variable '" + v + "' is used at the neighbour '" +
                                 edges[e].neighbour + "' but not bound there");
          return r;
        }
    }
    placeConditions(r, side, hostBound, edges);

    bool hostFacts = false;
    for (size_t i = 0; i < r.body.size(); ++i) hostFacts |= side[i] == kHost && nodeFact(r.body[i]);
    if (edges.size() == 1 && !hostFacts) {
      // Only the route at the host: the whole rule runs at the neighbour (§6.7).
      Rule moved = r;
      moved.body[edges[0].route] = inverseSubgoal(r, r.body[edges[0].route]);
      return rule(moved, inherited ? inherited : &ruleTypes(r));
    }
    return split(r, side, edges, *host, inherited ? *inherited : ruleTypes(r));
  }

  // Conditions go to a neighbour when everything they use is bound there and something is not
  // bound at the host; assignments first (to a fixed point), since they bind for later ones.
  void placeConditions(const Rule& r, std::vector<int>& side, VarSet& hostBound, std::vector<Edge>& edges) {
    auto place = [&](const VarList& uses) {
      for (size_t e = 0; e < edges.size(); ++e)
        if (!uses.empty() && allIn(uses, edges[e].bound) && !allIn(uses, hostBound))
          return static_cast<int>(e);
      return kHost;
    };
    auto boundAnywhere = [&](const std::string& v) {
      return hostBound.count(v) ||
             std::any_of(edges.begin(), edges.end(), [&](const Edge& e) { return e.bound.count(v) > 0; });
    };
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t i = 0; i < r.body.size(); ++i) {
        const Term& t = r.body[i];
        if (side[i] != kUndecided || t.kind != TermKind::Constraint || t.cond.kind != ExprKind::Compare ||
            t.cond.op != BinOp::Eq || t.cond.args.at(0).kind != ExprKind::Var ||
            boundAnywhere(t.cond.args[0].name))
          continue;
        VarList rhs;
        exprVars(t.cond.args.at(1), rhs);
        if (!std::all_of(rhs.begin(), rhs.end(), boundAnywhere)) continue;
        side[i] = place(rhs);
        (side[i] == kHost ? hostBound : edges[static_cast<size_t>(side[i])].bound)
            .insert(t.cond.args[0].name);
        changed = true;
      }
    }
    for (size_t i = 0; i < r.body.size(); ++i) {
      if (side[i] != kUndecided) continue;
      VarList uses;
      termVars(r.body[i], uses);
      side[i] = place(uses);
    }
  }

  // The inferred type of every variable of `r` (kept in typesOfRules_: a moved rule refers to them).
  const VarTypes& ruleTypes(const Rule& r) {
    if (!typing_) {
      // Expression types of the still unchanged program (it passed the type check: silent).
      SourceManager none;
      std::ostringstream ignored;
      Diagnostics quiet(none, ignored);
      typing_ = inferTypes(p_, quiet);
    }
    VarTypes& types = typesOfRules_.emplace_back();  // a variable nothing typed is an int, as in the checker
    for (const std::vector<Term>* ts : {&r.body, &r.head})
      for (const Term& t : *ts) eachExpr(t, [&](const Expr& e) { varTypes(e, *typing_, types); });
    return types;
  }

  Rule split(const Rule& r, const std::vector<int>& side, const std::vector<Edge>& edges,
             const std::string& host, VarTypes types) {
    VarList order;  // first occurrences: body, then head
    for (const std::vector<Term>* ts : {&r.body, &r.head})
      for (const Term& t : *ts) termVars(t, order);
    Rule out = r;
    out.body.clear();
    for (size_t e = 0; e < edges.size(); ++e) {
      const int edge = static_cast<int>(e);
      VarList restUses;
      for (size_t i = 0; i < r.body.size(); ++i)
        if (side[i] != edge) termVars(r.body[i], restUses);
      for (const Term& t : r.head) termVars(t, restUses);
      if (r.selector) restUses.push_back(r.selector->var);
      const VarSet rest(restUses.begin(), restUses.end());
      VarList vars;
      for (const std::string& v : order)
        if (v != host && edges[e].bound.count(v) && rest.count(v) &&
            std::find(vars.begin(), vars.end(), v) == vars.end())
          vars.push_back(v);
      std::stable_partition(vars.begin(), vars.end(),
                            [&](const std::string& v) { return types[v].kind == TypeKind::Int; });

      bool linear = false;
      for (size_t i = 0; i < r.body.size(); ++i)
        if (const PredInfo* pi = info(r.body[i]); pi && side[i] == edge) linear |= pi->linear;

      PredicateDecl helper;
      helper.loc = helper.nameLoc = r.loc;
      helper.name = "__mangledname";
      helper.name += std::to_string(++mangled_);
      helper.linear = linear;
      helper.generated = true;
      std::vector<Expr> args{var(r.loc, host)};
      helper.fields.push_back(
          FieldDecl{r.loc, FieldAgg::None, TypeExpr{TypeKind::Node, r.loc, {}, {}, {}}, {}});
      for (const std::string& v : vars) {
        TypeExpr type = types[v];
        type.loc = r.loc;
        helper.fields.push_back(FieldDecl{r.loc, FieldAgg::None, std::move(type), {}});
        args.push_back(var(r.loc, v));
      }
      const Mark mark = linear ? Mark::None : Mark::Persistent;

      Rule remote;
      remote.loc = r.loc;
      remote.kind = RuleKind::Linear;
      remote.generated = true;
      remote.body.push_back(inverseSubgoal(r, r.body[edges[e].route]));
      for (size_t i = 0; i < r.body.size(); ++i)
        if (side[i] == edge && i != edges[e].route) remote.body.push_back(r.body[i]);
      helper.sym = p_.symbols.intern(helper.name);
      preds_[helper.sym] = PredInfo{nullptr, linear, false, false};
      remote.head.push_back(subgoal(r.loc, mark, helper.name, args));
      const std::string helperName = helper.name;
      helpers_.push_back(std::move(helper));
      // Nodes beyond the neighbour: its rule spans nodes in turn (helpers numbered depth first).
      generatedRules_.push_back(rule(remote, &types));

      out.body.push_back(subgoal(r.loc, mark, helperName, std::move(args)));
    }
    for (size_t i = 0; i < r.body.size(); ++i)
      if (side[i] == kHost) out.body.push_back(r.body[i]);
    return out;
  }

  // `___inv(Y, X, R...)` for the route subgoal `r(X, Y, R...)`, creating the inverse route (and
  // its rule) on first use.
  Term inverseSubgoal(const Rule& r, const Term& route) {
    Term t = route;
    t.name = inverse(*info(route)->decl, r.loc);
    t.sym = p_.symbols.intern(t.name);
    std::swap(t.args[0], t.args[1]);
    return t;
  }

  std::string inverse(const PredicateDecl& route, SourceLoc ruleLoc) {
    auto [it, fresh] = inverseNames_.try_emplace(route.sym);
    if (!fresh) return it->second;
    it->second = "___" + std::string(route.name.rbegin(), route.name.rend());
    PredicateDecl d = route;
    d.name = it->second;
    d.route = d.reverseRoute = d.generated = true;
    d.action = d.imported = false;
    d.importedName.clear();
    d.importedFrom.clear();
    std::swap(d.fields[0], d.fields[1]);
    // A plain mirror of the route facts: an aggregate field is already aggregated at the route.
    for (FieldDecl& f : d.fields) f.agg = FieldAgg::None;
    // A fact at the neighbour when the rule it moved to is localized again, never an edge there.
    d.sym = p_.symbols.intern(d.name);
    preds_[d.sym] = PredInfo{nullptr, d.linear, false, false};
    inverses_.push_back(d);

    // r(X0, X1, R...) -o ___inv(X1, X0, R...), persistent for a persistent route.
    Rule rule;
    rule.loc = ruleLoc;
    rule.kind = RuleKind::Linear;
    rule.generated = true;
    std::vector<Expr> args;
    for (size_t i = 0; i < route.fields.size(); ++i) {
      std::string name = "X";  // appended: GCC 12 warns (-Wrestrict, false positive) on "X" + string&&
      name += std::to_string(i);
      args.push_back(var(ruleLoc, name));
    }
    const Mark mark = route.linear ? Mark::None : Mark::Persistent;
    rule.body.push_back(subgoal(ruleLoc, mark, route.name, args));
    std::swap(args[0], args[1]);
    rule.head.push_back(subgoal(ruleLoc, mark, d.name, std::move(args)));
    generatedRules_.push_back(std::move(rule));
    return it->second;
  }

  // A subgoal at a node that no chain of route subgoals leads to from the host.
  void unreachable(const Term& t, const std::string& host) {
    diag_.error(t.args[0].loc, "cannot localize this rule: '" + t.name + "' is at '" + *homeVar(t) +
                                   "', which no route subgoal leads to from the host '" + host +
                                   "' (a route leads from its first argument to its second)");
  }

  Program& p_;
  Diagnostics& diag_;
  std::unordered_map<Symbol, const TypeExpr*> aliases_;
  std::unordered_map<Symbol, PredInfo> preds_;
  std::unordered_map<Symbol, std::string> inverseNames_;  // route -> inverse name
  std::vector<Rule> generatedRules_;
  std::vector<PredicateDecl> helpers_;
  std::vector<PredicateDecl> inverses_;
  int mangled_ = 0;
  std::optional<Typing> typing_;
  std::deque<VarTypes> typesOfRules_;
};

}  // namespace

void localizeRules(Program& program, Diagnostics& diag) { Localizer(program, diag).run(); }

}  // namespace meldc
