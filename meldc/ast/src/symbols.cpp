#include "meldc/ast/program.hpp"
#include "meldc/ast/symbol.hpp"
#include "meldc/builtins.hpp"
#include "meldc/case_folding.hpp"

namespace meldc::ast {

Symbol SymbolTable::intern(std::string_view name) {
  std::string folded = lower(name);
  auto [it, added] = ids_.try_emplace(folded, static_cast<std::uint32_t>(names_.size()));
  if (added) names_.push_back(std::move(folded));
  return Symbol{it->second};
}

Symbol SymbolTable::find(std::string_view name) const {
  auto it = ids_.find(lower(name));
  return it == ids_.end() ? Symbol{} : Symbol{it->second};
}

namespace {

class Interner {
 public:
  explicit Interner(SymbolTable& table) : table_(table) {}

  void program(Program& p) {
    for (const BuiltinPredicate& b : builtinPredicates()) table_.intern(b.name);
    for (const BuiltinFunction& b : builtinFunctions()) table_.intern(b.name);
    for (NodeTypeDecl& n : p.nodeTypes) n.sym = table_.intern(n.name);
    for (TypeAliasDecl& a : p.typeAliases) {
      a.sym = table_.intern(a.name);
      type(a.type);
    }
    for (PredicateDecl& d : p.predicates) {
      d.sym = table_.intern(d.name);
      for (FieldDecl& f : d.fields) type(f.type);
    }
    for (Directive& d : p.directives) {
      if (!d.name.empty()) d.sym = table_.intern(d.name);
      if (!d.other.empty()) d.otherSym = table_.intern(d.other);
    }
    for (ExternDecl& e : p.externs) {
      e.sym = table_.intern(e.name);
      type(e.result);
      for (FieldDecl& f : e.params) type(f.type);
    }
    for (ConstDecl& c : p.consts) {
      c.sym = table_.intern(c.name);
      expr(c.value);
    }
    for (FunDecl& f : p.funs) {
      f.sym = table_.intern(f.name);
      for (FunParam& param : f.params) type(param.type);
      type(f.result);
      expr(f.body);
    }
    for (Rule& r : p.rules) {
      terms(r.body);
      terms(r.head);
    }
    GroundFacts& ground = p.groundFacts;
    ground.nameSyms.clear();
    for (const std::string& n : ground.names) ground.nameSyms.push_back(table_.intern(n));
  }

 private:
  void type(TypeExpr& t) {
    if (t.kind == TypeKind::Named) t.sym = table_.intern(t.name);
    for (TypeExpr& a : t.args) type(a);
  }
  void expr(Expr& e) {
    if (e.kind == ExprKind::Const || e.kind == ExprKind::Call) e.sym = table_.intern(e.name);
    for (Expr& a : e.args) expr(a);
  }
  void terms(std::vector<Term>& ts) {
    for (Term& t : ts) term(t);
  }
  void term(Term& t) {
    if (t.kind == TermKind::Subgoal) t.sym = table_.intern(t.name);
    for (Expr& a : t.args) expr(a);
    expr(t.cond);
    for (AggSpec& s : t.specs) {
      if (!s.function.empty()) s.functionSym = table_.intern(s.function);
      expr(s.start);
    }
    terms(t.body);
    terms(t.perMatch);
    terms(t.head);
    terms(t.elseHead);
  }

  SymbolTable& table_;
};

}  // namespace

void internNames(Program& program) { Interner(program.symbols).program(program); }

}  // namespace meldc::ast
