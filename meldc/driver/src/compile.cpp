#include "meldc/compile.hpp"

#include "meldc/includes.hpp"
#include "meldc/lower.hpp"
#include "meldvm/bytecode.hpp"

namespace meldc {

std::unique_ptr<meldvm::Program> compileProgram(FrontEndInput input, SourceManager& sources,
                                                Diagnostics& diag, bool useStdlib) {
  if (useStdlib && !defaultStdlibDir().empty()) input.includeDirs.push_back(defaultStdlibDir());
  std::optional<ast::Program> ast = runFrontEnd(input, sources, diag);
  if (!ast) return nullptr;
  std::unique_ptr<meldvm::Program> program = lowerProgram(*ast, sources, diag);
  if (!program) return nullptr;
  try {
    meldvm::verifyProgram(*program);
  } catch (const meldvm::BytecodeError& e) {
    throw InternalCompilerError(std::string("the compiled program fails verification: ") + e.what());
  }
  return program;
}

}  // namespace meldc
