// Native code for Meld programs (the LLVM backend). The verified bytecode of every native block
// (meldvm::nativeCodeBlocks) is lowered to LLVM IR that calls the VM's helpers (native_abi.h) for
// everything but register arithmetic, jumps and stepping through facts, optimised, then either printed
// (`meldc --emit=llvm`), written as a shared object (`meldc --emit=native`) or compiled in-process
// (`meld --jit`).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "meldvm/native_abi.h"
#include "meldvm/program.hpp"

namespace meldc::native {

class NativeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `cpu`: the processor to compile for: "generic" (any machine of this architecture), "native" (this
// one's) or an LLVM processor name; an unknown name throws NativeError.
bool knownCpu(const std::string& cpu);

// Told how far a compilation is: `done` of `total` parts compiled. Called from the compiling
// threads, one call at a time.
using CompileProgress = std::function<void(std::size_t done, std::size_t total)>;

// The program's native blocks as optimised LLVM IR text.
std::string llvmText(const meldvm::Program& program, const std::string& cpu = "native");

// The program as a shared object (`meldc --emit=native`): its native code, and its bytecode for
// the tables (native_abi.h). Compiled on up to `jobs` threads (0: one per processor; the file is the
// same whatever the number). Needs the system linker (`ld`, or $MELD_LD); throws NativeError.
void writeSharedObject(const meldvm::Program& program, const std::string& path,
                       const std::string& cpu = "generic", unsigned jobs = 0,
                       const CompileProgress& progress = {});

// The program compiled in this process. The entry of native block k is entries()[k]; the code lives
// as long as the Jit.
class Jit {
 public:
  // Compiled on one thread per processor, telling `progress`; throws NativeError.
  static std::unique_ptr<Jit> compile(const meldvm::Program& program, const CompileProgress& progress = {});
  ~Jit();
  const std::vector<meld_native_block>& entries() const { return entries_; }

 private:
  struct Engine;
  Jit();
  std::unique_ptr<Engine> engine_;
  std::vector<meld_native_block> entries_;
};

}  // namespace meldc::native
