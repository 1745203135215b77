// Pass: type checking and inference (§3.2) after name resolution. Every variable of a rule gets
// one type from the predicate fields, operators and functions it meets; integer literals adapt to
// float contexts (variables do not: `float(X)`).
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

void checkTypes(const ast::Program& program, Diagnostics& diag);

}  // namespace meldc
