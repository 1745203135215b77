// Pass: homes of body facts (§5.2, §6.7). Every body subgoal must live at the rule's host (the
// home of the first body subgoal), at a node reached from it through route subgoals, or at a
// thread (thread predicates); otherwise the rule cannot be localized ("bad home argument").
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

void checkHomes(const ast::Program& program, Diagnostics& diag);

}  // namespace meldc
