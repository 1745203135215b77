// vsim --program: a Meld program as the block program of every block (the VM behind the block
// ABI, vm/robots/include/meldvm/block_runtime.hpp).
#pragma once

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "meldvm/native_code.hpp"
#include "meldvm/native_library.hpp"
#include "meldvm/program.hpp"

namespace vsim {

// A .meld file is compiled with node ids = block ids (robots: the program runs on a world's blocks;
// false: on its own graph, as `meld` runs it, for the multicore target); compile errors go to
// `diagnostics` in the usual file:line:col form (nullptr: discarded); a .mbc file is loaded and
// verified. Throws ProgramLoadError.
class ProgramLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
std::unique_ptr<meldvm::Program> loadMeldProgram(const std::string& path,
                                                 const std::vector<std::string>& includeDirs,
                                                 std::ostream* diagnostics, bool robots = true);

// A Meld program with its native code, when it has some: a native shared object (`meldc
// --emit=native`), or what the JIT made of a .meld or .mbc file (vsim --jit).
struct MeldCode {
  std::unique_ptr<meldvm::Program> source;         // compiled, or read from bytecode
  std::unique_ptr<meldvm::NativeLibrary> library;  // a native .so (owns its program and code)
  std::shared_ptr<void> jit;                       // keeps the JIT's code alive
  std::unique_ptr<meldvm::NativeCode> jitCode;
  const meldvm::Program& program() const { return library ? library->program() : *source; }
  const meldvm::NativeCode* native() const { return library ? &library->code() : jitCode.get(); }
};

// Compiles a program to native code in this process (vsim --jit). The LLVM backend is linked into
// the vsim executable only, which passes one to the session; throws ProgramLoadError.
class NativeCompiler {
 public:
  virtual ~NativeCompiler() = default;
  virtual void compile(MeldCode& code) const = 0;  // sets code.jit and code.jitCode
};

// loadMeldProgram, and a .so file as a native program; with `jit`, a .meld or .mbc program is
// compiled to native code too.
std::unique_ptr<MeldCode> loadMeldCode(const std::string& path, const std::vector<std::string>& includeDirs,
                                       std::ostream* diagnostics, bool robots, const NativeCompiler* jit);

}  // namespace vsim
