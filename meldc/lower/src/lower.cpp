#include "meldc/lower.hpp"

#include "lower_context.hpp"

namespace meldc {

std::unique_ptr<meldvm::Program> lowerProgram(const ast::Program& program, SourceManager& sources,
                                              Diagnostics& diag) {
  auto out = std::make_unique<meldvm::Program>();
  Lowering L(program, sources, diag, *out);
  const int errors = diag.errorCount();
  // Typed again here: the front end's passes after type checking (localization) add rules.
  L.typing = inferTypes(program, diag);
  if (diag.errorCount() > errors) return nullptr;
  lowerDeclarations(L);
  if (diag.errorCount() > errors) return nullptr;
  lowerConstantsAndFunctions(L);
  lowerAxioms(L);
  lowerRules(L);
  if (diag.errorCount() > errors) return nullptr;
  return out;
}

}  // namespace meldc
