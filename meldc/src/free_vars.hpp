// The variables an expression reads: every variable occurrence not bound by an enclosing `let`
// (§5.5), in textual order. Shared by the passes that ask which variables a term needs.
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

}  // namespace meldc
