/* The seam between natively compiled Meld code and the VM (plain C).
 *
 * The LLVM backend (meldc/native) lowers the verified bytecode of a code block to functions of type
 * meld_native_block: one for the block's start and one for the body of each of its loops. Register
 * arithmetic, moves of unboxed values and jumps become machine code; everything that touches the
 * fact store, the heap, messages or the scheduler is a call to one of the helpers below, which run
 * the interpreter's own code for that instruction (the PostgreSQL JIT pattern), so that bytecode
 * and native code agree by construction.
 *
 * A block function returns what the interpreter's exec() returns for the same code: 0 the body did
 * not fire, 1 it fired, 2 return (RET, or the run is stopping). `regs` are the frame's registers,
 * 8 bytes each (meldvm::Value). */
#ifndef MELDVM_NATIVE_ABI_H
#define MELDVM_NATIVE_ABI_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever a helper, its meaning or the block signature changes. */
#define MELD_NATIVE_ABI_VERSION 3u

typedef struct meld_native_vm meld_native_vm;       /* the interpreter running the block */
typedef struct meld_native_frame meld_native_frame; /* its frame (registers, loop slots) */
typedef struct meld_native_helpers meld_native_helpers;

typedef int32_t (*meld_native_block)(const meld_native_helpers* h, meld_native_vm* vm, meld_native_frame* f,
                                     uint64_t* regs);
typedef void (*meld_native_step)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc);

struct meld_native_helpers {
  uint32_t abi_version;
  /* Runs the loop instruction at pc (ITER, ITER_KEY or ITER_SORTED), calling `body` for each
   * fact it binds; returns 1 if a body fired, 2 if the run is stopping, else 0. */
  int32_t (*loop)(const meld_native_helpers* h, meld_native_vm* vm, meld_native_frame* f, uint32_t pc,
                  meld_native_block body);
  /* steps[OPCODE] runs the straight-on instruction at pc, which has that opcode (every opcode that
   * neither jumps nor ends a block has one): no dispatch on the opcode at run time. */
  const meld_native_step* steps;
  /* TEST at pc: 1 if the field equals the register. */
  int32_t (*test)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc);
  /* FIRE (count_rule = 1) or CFIRE (0) at pc: consumes the linear facts of its slots. */
  void (*fire)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc, int32_t count_rule);
  /* RET_IF_UPDATED: 1 if an UPDATE ran in this frame. */
  int32_t (*updated)(meld_native_frame* f);
  /* The arguments of the fact bound to loop slot `slot` (8 bytes each, home excluded), valid until
   * the next instruction that stores a fact: LOAD into an unboxed register reads them directly. */
  const uint64_t* (*slot_args)(meld_native_vm* vm, meld_native_frame* f, uint32_t slot);
  /* FIRE of a block whose loops consume nothing from its first slot on: counts the rule only. */
  void (*rule_fired)(meld_native_vm* vm);
  /* Drops the last reference to a boxed value of type `type` (native code counts references
   * itself: a boxed value points at its 32-bit count; this is for when it would reach zero). */
  void (*release_last)(meld_native_vm* vm, uint32_t type, uint64_t value);
};

/* What a native shared object (`meldc --emit=native`) exports: meld_native_program() returns its
 * description. The program's tables travel as its bytecode (verified again when loaded); block k
 * of meldvm::nativeCodeBlocks runs blocks[k]. */
#define MELD_NATIVE_MAGIC 0x4e444c4du /* "MLDN" */
typedef struct meld_native_program_desc {
  uint32_t magic;
  uint32_t abi_version;      /* MELD_NATIVE_ABI_VERSION it was built for */
  uint32_t bytecode_version; /* meldvm::kBytecodeVersion of the bytecode below */
  uint32_t block_count;
  const uint8_t* bytecode;
  uint64_t bytecode_size;
  const meld_native_block* blocks;
} meld_native_program_desc;

#define MELD_NATIVE_ENTRY "meld_native_program"
typedef const meld_native_program_desc* (*meld_native_entry)(void);

#ifdef __cplusplus
}
#endif

#endif /* MELDVM_NATIVE_ABI_H */
