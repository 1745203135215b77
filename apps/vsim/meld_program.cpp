#include "meld_program.hpp"

#include <ostream>
#include <sstream>

#include "meldc/compile.hpp"
#include "meldc/source.hpp"
#include "meldvm/bytecode.hpp"

namespace vsim {

std::unique_ptr<meldvm::Program> loadMeldProgram(const std::string& path,
                                                 const std::vector<std::string>& includeDirs,
                                                 std::ostream* diagnostics, bool robots) {
  const bool bytecode = path.size() >= 4 && path.compare(path.size() - 4, 4, ".mbc") == 0;
  if (bytecode) {
    try {
      return meldvm::readBytecodeFile(path);
    } catch (const meldvm::BytecodeError& e) {
      throw ProgramLoadError(e.what());  // the message names the file
    }
  }
  meldc::SourceManager sources;
  std::ostringstream discarded;
  meldc::Diagnostics diag(sources, diagnostics ? *diagnostics : discarded);
  meldc::FrontEndInput input{path, includeDirs, {}};
  input.identityNodes = robots;  // node ids are block ids
  std::unique_ptr<meldvm::Program> program;
  try {
    program = meldc::compileProgram(input, sources, diag);
  } catch (const meldc::InternalCompilerError& e) {
    throw ProgramLoadError(std::string("internal compiler error: ") + e.what());
  }
  if (!program) throw ProgramLoadError(path + ": error: the Meld program has errors (see above)");
  return program;
}

std::unique_ptr<MeldCode> loadMeldCode(const std::string& path, const std::vector<std::string>& includeDirs,
                                       std::ostream* diagnostics, bool robots, const NativeCompiler* jit) {
  auto code = std::make_unique<MeldCode>();
  if (meldvm::isNativeProgramFile(path)) {
    if (jit) throw ProgramLoadError(path + ": native code already: --jit is for .meld and .mbc programs");
    try {
      code->library = meldvm::NativeLibrary::open(path);
    } catch (const meldvm::BytecodeError& e) {
      throw ProgramLoadError(e.what());  // the message names the file
    }
    return code;
  }
  code->source = loadMeldProgram(path, includeDirs, diagnostics, robots);
  if (jit) jit->compile(*code);
  return code;
}

}  // namespace vsim
