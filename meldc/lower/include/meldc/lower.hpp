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

// Returns nullptr when the back end finds an error the checks leave to it (a construct out of its
// place, §5.2/§5.3; reported to `diag` with its position).
std::unique_ptr<meldvm::Program> lowerProgram(const ast::Program& program, SourceManager& sources,
                                              Diagnostics& diag);

}  // namespace meldc
