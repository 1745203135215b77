#include "meld_program.hpp"

#include <iostream>

#include "meldc/diagnostics.hpp"
#include "meldc/frontend.hpp"
#include "meldc/includes.hpp"
#include "meldc/lower.hpp"
#include "meldc/source.hpp"
#include "meldvm/bytecode.hpp"

namespace vsim {

std::unique_ptr<meldvm::Program> loadMeldProgram(const std::string& path,
                                                 const std::vector<std::string>& includeDirs) {
  const bool bytecode = path.size() >= 4 && path.compare(path.size() - 4, 4, ".mbc") == 0;
  if (bytecode) {
    try {
      return meldvm::readBytecodeFile(path);
    } catch (const meldvm::BytecodeError& e) {
      throw ProgramLoadError(e.what());  // the message names the file
    }
  }
  meldc::SourceManager sources;
  meldc::Diagnostics diag(sources, std::cerr);
  meldc::FrontEndInput input{path, includeDirs, {}};
  // After the -I folders, the target include files of stdlib/ (`include #blinkyblocks.meld`).
  if (const std::string stdlib = meldc::defaultStdlibDir(); !stdlib.empty())
    input.includeDirs.push_back(stdlib);
  input.identityNodes = true;
  std::optional<meldc::ast::Program> ast = meldc::runFrontEnd(input, sources, diag);
  std::unique_ptr<meldvm::Program> program = ast ? meldc::lowerProgram(*ast, sources, diag) : nullptr;
  if (!program) throw ProgramLoadError(path + ": error: the Meld program has errors (see above)");
  try {
    meldvm::verifyProgram(*program);
  } catch (const meldvm::BytecodeError& e) {
    throw ProgramLoadError(std::string("internal compiler error: the compiled program fails verification: ") +
                           e.what());
  }
  return program;
}

}  // namespace vsim
