// A program's native blocks as one optimised LLVM module (native_module.cpp).
#pragma once

#include <memory>
#include <string>

#include "meldc/native.hpp"

namespace llvm {
class LLVMContext;
class Module;
class TargetMachine;
}  // namespace llvm

namespace meldc::native {

// The name of native block k's entry function.
std::string blockSymbol(std::size_t k);

// The host's target machine (the native target is initialised on first use); throws NativeError.
// The target machine of this process's architecture for `cpu` (native.hpp).
std::unique_ptr<llvm::TargetMachine> targetMachine(const std::string& cpu);

// Lowers every native block (meldvm::nativeCodeBlocks) and optimises the module at O2 for `target`.
std::unique_ptr<llvm::Module> buildModule(const meldvm::Program& program, llvm::LLVMContext& context,
                                          llvm::TargetMachine& target);

}  // namespace meldc::native
