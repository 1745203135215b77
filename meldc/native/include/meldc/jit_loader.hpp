// Native code compiled in this process (meld --jit, vsim --jit), by the LLVM backend that lives in
// a module (libmeld_jit.so) loaded on the first compilation: a program that only runs bytecode or
// a shared object never loads LLVM (start-up in milliseconds and megabytes, not tens of each).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "meldc/jit_module.h"
#include "meldvm/program.hpp"

namespace meldc::native {

class JitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class JitCode {
 public:
  using Progress = std::function<void(std::size_t done, std::size_t total)>;

  // Loads the module if need be and compiles the program; throws JitError (module missing or
  // stale, or the backend's own error).
  static std::unique_ptr<JitCode> compile(const meldvm::Program& program, const Progress& progress = {});
  ~JitCode();
  JitCode(const JitCode&) = delete;
  JitCode& operator=(const JitCode&) = delete;

  const std::vector<meld_native_block>& entries() const { return entries_; }

  // Where the module is looked for, in order: $MELD_JIT_MODULE, <bin>/../lib/meld/libmeld_jit.so
  // (an installation), then the build tree's.
  static std::vector<std::string> modulePlaces();

 private:
  JitCode() = default;
  meld_jit_release_fn release_ = nullptr;
  void* owner_ = nullptr;
  std::vector<meld_native_block> entries_;
};

}  // namespace meldc::native
