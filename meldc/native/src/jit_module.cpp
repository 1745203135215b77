// libmeld_jit.so: the LLVM backend's JIT behind the C seam of jit_module.h, for the programs that
// load it on demand (jit_loader.cpp). Only the functions below are exported.
#include "meldc/jit_module.h"

#include <exception>

#include "meldc/native.hpp"
#include "support/toolchain_module.hpp"

#define MELD_JIT_EXPORT extern "C" __attribute__((visibility("default")))

using support::copyModuleMessage;

MELD_JIT_EXPORT int meld_jit_version() { return MELD_JIT_MODULE_VERSION; }

MELD_JIT_EXPORT int meld_jit_compile(const void* program, meld_jit_progress progress, void* context,
                                     meld_jit_result* result, char* error, size_t error_size) {
  try {
    meldc::native::CompileProgress tell;
    if (progress) tell = [&](std::size_t done, std::size_t total) { progress(done, total, context); };
    auto jit = meldc::native::Jit::compile(*static_cast<const meldvm::Program*>(program), tell);
    result->entries = jit->entries().data();
    result->count = jit->entries().size();
    result->owner = jit.release();
    return 0;
  } catch (const std::exception& e) {
    copyModuleMessage(e.what(), error, error_size);
  } catch (...) {
    copyModuleMessage("unknown error", error, error_size);
  }
  return 1;
}

MELD_JIT_EXPORT void meld_jit_release(void* owner) { delete static_cast<meldc::native::Jit*>(owner); }
