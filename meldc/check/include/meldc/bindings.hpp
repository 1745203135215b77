// Pass: variable binding (§5.2, §5.3): every variable of a head or of a body condition must be
// bound by a body subgoal, an assignment, `exists`, or the construct that declares it.
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

void checkBindings(const ast::Program& program, Diagnostics& diag);

}  // namespace meldc
