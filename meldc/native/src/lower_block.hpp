// Lowering one code block to LLVM functions (lower_block.cpp); used by native_module.cpp.
#pragma once

#include <string>

#include "meldc/native.hpp"

namespace llvm {
class Function;
class FunctionType;
class LLVMContext;
class Module;
class StructType;
}  // namespace llvm

namespace meldc::native {

// meld_native_block's type.
llvm::FunctionType* blockFunctionType(llvm::LLVMContext& context);

// The LLVM types of native_abi.h, made once per module.
struct NativeTypes {
  explicit NativeTypes(llvm::Module& m);
  llvm::Module& module;
  llvm::LLVMContext& context;
  llvm::StructType* helpersType;     // meld_native_helpers
  llvm::FunctionType* blockType;     // meld_native_block
  llvm::FunctionType* bodyType;      // a loop body run by native code: the block's arguments, then the loops
  llvm::StructType* loopStructType;  // meld_native_loop
  llvm::StructType* slotType;        // meld_native_slot
  llvm::StructType* contextType;     // meld_native_context
  llvm::StructType* tableType;       // meld_native_table
  llvm::StructType* fieldIndexType;  // meld_native_field_index
  llvm::StructType* frameHeadType;   // meld_native_frame_head
  llvm::StructType* consumedType;    // meld_native_consumed
  llvm::StructType* arrayType;       // meld_native_array
  llvm::StructType* heapType;        // meld_native_heap
  llvm::FunctionType *loopType, *stepType, *testType, *consumeType, *updatedType, *slotArgsType,
      *releaseLastType, *loopBeginType, *builtinType;
  llvm::FunctionType *deriveType, *sendType;  // sendType: UPDATE's helper too
};

// What a block is run as: a rule (Machine::runRule), a persistent process (its slot 0 holds the
// triggering fact), or anything else (a function, the globals' initialiser).
enum class BlockKind { Rule, Process, Other };

// Lowers the block's code; returns its entry function, external and named `name` (the loop bodies
// are internal functions named after it).
llvm::Function* lowerBlock(NativeTypes& types, const meldvm::Program& program, const meldvm::CodeBlock& block,
                           const std::string& name, BlockKind kind);

}  // namespace meldc::native
