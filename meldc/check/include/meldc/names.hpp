// Name resolution (case-insensitive, §1.3): declarations must be unique; every predicate, type,
// constant and function that is used must exist, with the declared number of arguments; the
// `!`/`?`/`$` marks must fit the kind of predicate (§3.2); instruction predicates only in heads.
// Reports errors (and the warnings cl-meld gives for missing `!`); changes nothing.
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

void resolveNames(const ast::Program& program, Diagnostics& diag);

}  // namespace meldc
