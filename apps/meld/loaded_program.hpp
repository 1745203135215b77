// What meld runs: a program compiled in memory (.meld), loaded from bytecode (.mbc) or from a
// native shared object (.so, `meldc --emit=native`), with its native code (the .so's, or the JIT's
// with --jit) when it has some.
#pragma once

#include <memory>

#include "meldc/jit_loader.hpp"
#include "meldvm/native_code.hpp"
#include "meldvm/native_library.hpp"
#include "meldvm/program.hpp"
#include "options.hpp"

namespace meldapp {

struct LoadedProgram {
  const meldvm::Program* program = nullptr;
  const meldvm::NativeCode* native = nullptr;  // nullptr: the interpreter runs everything
  // Owners (the native code must outlive every machine that runs it).
  std::unique_ptr<meldvm::Program> source;
  std::unique_ptr<meldvm::NativeLibrary> library;
  std::unique_ptr<meldc::native::JitCode> jit;
  std::unique_ptr<meldvm::NativeCode> jitCode;
};

// Compiles or loads the program named by the options; on failure prints why, sets the exit status
// and returns nullptr.
std::unique_ptr<LoadedProgram> loadProgram(const Options& options, int& status);

}  // namespace meldapp
