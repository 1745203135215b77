// Native code compiled in this process (meld --jit, vsim --jit), by the LLVM backend that lives in
// a module (libmeld_jit.so) loaded on the first compilation: a program that only runs bytecode or
// a shared object never loads LLVM (start-up in milliseconds and megabytes, not tens of each).
// Errors and progress are native.hpp's, whose declarations need no LLVM.
#pragma once

#include <memory>
#include <vector>

#include "meldc/jit_module.h"
#include "meldc/native.hpp"
#include "meldvm/program.hpp"

namespace meldc::native {

class JitCode {
 public:
  // Loads the module if need be and compiles the program; throws NativeError (module missing,
  // foreign or stale, or the backend's own error). The module is $MELD_JIT_MODULE when that is
  // set, else <bin>/../lib/meld/libmeld_jit.so (an installation), else this build tree's.
  static std::unique_ptr<JitCode> compile(const meldvm::Program& program, const CompileProgress& progress = {});
  ~JitCode();
  JitCode(const JitCode&) = delete;
  JitCode& operator=(const JitCode&) = delete;

  const std::vector<meld_native_block>& entries() const { return entries_; }

 private:
  JitCode() = default;
  meld_jit_release_fn release_ = nullptr;
  void* owner_ = nullptr;
  std::vector<meld_native_block> entries_;
};

}  // namespace meldc::native
