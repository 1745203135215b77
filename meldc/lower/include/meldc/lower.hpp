// The back end of meldc: lowers the checked AST (after localization and node renumbering) to the
// VM's Program (meldvm/program.hpp): type and predicate tables, nodes, constants, functions,
// rule 0 with the axioms, the numbered rules and the persistent processes, following the code
// contract of the VM engine (opcodes.def).
#pragma once

#include <memory>

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"
#include "meldvm/program.hpp"

namespace meldc {

// Returns nullptr when the program uses something the back end cannot compile (reported to
// `diag` as "... is not supported").
std::unique_ptr<meldvm::Program> lowerProgram(const ast::Program& program, SourceManager& sources,
                                              Diagnostics& diag);

}  // namespace meldc
