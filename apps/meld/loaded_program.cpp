#include "loaded_program.hpp"

#include <unistd.h>

#include <iostream>

#include "meldc/compile_progress_line.hpp"
#include "meldc/frontend_loader.hpp"
#include "meldvm/bytecode.hpp"

namespace meldapp {

namespace {

bool endsWith(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

std::unique_ptr<meldvm::Program> compileSource(const Options& options, int& status) {
  try {
    auto program =
        meldc::compileThroughModule(options.program, options.includeDirs, options.defines, std::cerr);
    if (!program) status = kExitCompileErrors;
    return program;
  } catch (const meldc::FrontEndInternalError& e) {
    std::cerr << "meld: internal compiler error: " << e.what() << "\n";
    status = 70;
    return nullptr;
  } catch (const meldc::FrontEndModuleError& e) {
    std::cerr << "meld: error: " << e.what() << "\n";
    status = kExitCompileErrors;
    return nullptr;
  }
}

}  // namespace

std::unique_ptr<LoadedProgram> loadProgram(const Options& options, int& status) {
  auto loaded = std::make_unique<LoadedProgram>();
  try {
    if (meldvm::isNativeProgramFile(options.program)) {
      if (options.jit) {
        std::cerr << "meld: error: " << options.program
                  << " is native code already: --jit is for .meld and .mbc\n";
        status = kExitUsage;
        return nullptr;
      }
      loaded->library = meldvm::NativeLibrary::open(options.program);
      loaded->program = &loaded->library->program();
      loaded->native = &loaded->library->code();
      return loaded;
    }
    if (endsWith(options.program, ".mbc"))
      loaded->source = meldvm::readBytecodeFile(options.program);
    else if (!(loaded->source = compileSource(options, status)))
      return nullptr;
  } catch (const meldvm::BytecodeError& e) {
    std::cerr << "meld: error: " << e.what() << "\n";  // the message names the file
    status = kExitBadBytecode;
    return nullptr;
  }
  loaded->program = loaded->source.get();
  if (!options.jit) return loaded;
  try {
    meldc::CompileProgressLine progress("meld", isatty(STDERR_FILENO));
    loaded->jit = meldc::native::JitCode::compile(
        *loaded->program, [&](std::size_t done, std::size_t total) { progress.update(done, total); });
  } catch (const meldc::native::NativeError& e) {
    std::cerr << "meld: error: " << options.program << ": native code: " << e.what() << '\n';
    status = kExitRuntimeError;
    return nullptr;
  }
  loaded->jitCode = std::make_unique<meldvm::NativeCode>(*loaded->program, loaded->jit->entries());
  loaded->native = loaded->jitCode.get();
  return loaded;
}

}  // namespace meldapp
