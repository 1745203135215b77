// A program's native blocks as optimised LLVM modules (native_module.cpp) and as object code
// compiled on several threads (object_code.cpp).
#pragma once

#include <llvm/ADT/SmallVector.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "meldc/native.hpp"

namespace llvm {
class LLVMContext;
class Module;
class TargetMachine;
}  // namespace llvm

namespace meldc::native {

// The name of native block k's entry function.
std::string blockSymbol(std::size_t k);

// The target machine of this process's architecture for `cpu` (native.hpp); the native target is
// initialised on first use. Throws NativeError.
std::unique_ptr<llvm::TargetMachine> targetMachine(const std::string& cpu);

// Native blocks [first, last) of meldvm::nativeCodeBlocks: one module, compiled on one thread.
struct BlockRange {
  std::size_t first = 0, last = 0;
};

// The blocks cut into runs of about the same amount of bytecode. The cut depends on the program
// only, never on the number of threads, so that the code is the same whatever -j says. At least
// one range (an empty one when the program has no native block).
std::vector<BlockRange> partitionBlocks(const std::vector<const meldvm::CodeBlock*>& blocks);

// Lowers `blocks` [range.first, range.last) (meldvm::nativeCodeBlocks of the program) and
// optimises the module for `target`.
std::unique_ptr<llvm::Module> buildModule(const meldvm::Program& program,
                                          const std::vector<const meldvm::CodeBlock*>& blocks,
                                          llvm::LLVMContext& context, llvm::TargetMachine& target,
                                          BlockRange range);

// Called with partition k's module before it is emitted (shared_object.cpp adds the description).
using ModuleFinisher = std::function<void(llvm::Module&, std::size_t partition)>;

// The object code of each partition of partitionBlocks, in order, compiled for `cpu` on up to
// `jobs` threads (0: one per processor), telling `progress` after each partition. Throws
// NativeError (the first error of any thread).
std::vector<llvm::SmallVector<char, 0>> compileObjects(const meldvm::Program& program, const std::string& cpu,
                                                       unsigned jobs, const ModuleFinisher& finish = {},
                                                       const CompileProgress& progress = {});

}  // namespace meldc::native
