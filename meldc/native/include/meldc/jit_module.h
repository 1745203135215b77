/* The seam between the programs that may compile Meld to native code in their own process
 * (meld --jit, vsim --jit) and the module that does it (libmeld_jit.so, which holds the LLVM
 * backend and links LLVM). The programs load the module only when native code is asked for, so
 * that running bytecode never loads LLVM (jit_loader.hpp). Both sides come from one build: the
 * program is passed as the C++ object it is, and the version guards against a stale module. */
#pragma once

#include <stddef.h>

#include "meldvm/native_abi.h"

#define MELD_JIT_MODULE_VERSION 1

#ifdef __cplusplus
namespace meldvm {
struct Program;
}
extern "C" {
#endif

typedef void (*meld_jit_progress)(size_t done, size_t total, void* context);

typedef struct meld_jit_result {
  void* owner;                      /* keeps the code alive: give it to meld_jit_release */
  const meld_native_block* entries; /* the entry of native block k (meldvm::nativeCodeBlocks) */
  size_t count;
} meld_jit_result;

/* The module's version, MELD_JIT_MODULE_VERSION when it matches the program. */
typedef int (*meld_jit_version_fn)(void);
/* Compiles the program (a const meldvm::Program*): 0 and *result filled, or non-zero with the
 * reason in error (NUL-terminated, cut to error_size). Never throws. */
typedef int (*meld_jit_compile_fn)(const void* program, meld_jit_progress progress, void* context,
                                   meld_jit_result* result, char* error, size_t error_size);
typedef void (*meld_jit_release_fn)(void* owner);

#ifdef __cplusplus
}
#endif
