// Walks over the variables of expressions, shared by the passes that ask which variables a term
// binds or needs (bindings check, localization, lowering).
#pragma once

#include <set>
#include <string>

#include "meldc/ast/expr.hpp"

namespace meldc {

template <class F>
void forEachFreeVar(const ast::Expr& e, F&& f, const std::set<std::string>& local = {}) {
  if (e.kind == ast::ExprKind::Var) {
    if (!local.count(e.name)) f(e);
    return;
  }
  if (e.kind == ast::ExprKind::Let) {
    forEachFreeVar(e.args.at(0), f, local);
    std::set<std::string> inner = local;
    inner.insert(e.name);
    forEachFreeVar(e.args.at(1), f, inner);
    return;
  }
  for (const ast::Expr& a : e.args) forEachFreeVar(a, f, local);
}

// The variables of a body subgoal argument (§5.2): its pattern part (a variable, a list or struct
// pattern) binds them -- bind(variable) --; any other expression only tests a value, so its
// variables must be bound elsewhere -- test(variable).
template <class Bind, class Test>
void forEachPatternVar(const ast::Expr& e, Bind&& bind, Test&& test) {
  switch (e.kind) {
    case ast::ExprKind::Var:
      bind(e);
      return;
    case ast::ExprKind::List:
    case ast::ExprKind::Struct:
      for (const ast::Expr& a : e.args) forEachPatternVar(a, bind, test);
      return;
    default:
      forEachFreeVar(e, test);
  }
}

}  // namespace meldc
