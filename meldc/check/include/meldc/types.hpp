// Pass: type checking and inference (§3.2) after name resolution. Every variable of a rule gets
// one type from the predicate fields, operators and functions it meets; integer literals adapt to
// float contexts (variables do not: `float(X)`).
#pragma once

#include <map>
#include <string>
#include <unordered_map>

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

void checkTypes(const ast::Program& program, Diagnostics& diag);

// The inferred types the back end needs, keyed by AST address (valid while the program is not
// modified). Types are concrete: aliases and node subtypes are resolved (`node`), an integer
// literal that may be either numeric type is `int`, and a type nothing constrains is `int`.
struct Typing {
  std::unordered_map<const ast::Expr*, ast::TypeExpr> exprs;
  // Aggregate constructs (§5.3.4): the type of one aggregated value (the spec variable in the body).
  std::unordered_map<const ast::AggSpec*, ast::TypeExpr> aggItems;
  std::unordered_map<ast::Symbol, ast::TypeExpr> consts;  // constant -> its type
  const ast::TypeExpr* of(const ast::Expr& e) const {
    auto it = exprs.find(&e);
    return it == exprs.end() ? nullptr : &it->second;
  }
};

// Runs the checker of checkTypes and records the type of every expression.
Typing inferTypes(const ast::Program& program, Diagnostics& diag);

}  // namespace meldc
