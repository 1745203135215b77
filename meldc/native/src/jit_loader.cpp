#include "meldc/jit_loader.hpp"

#include <dlfcn.h>

#include <string>

#include "support/toolchain_module.hpp"

namespace meldc::native {

namespace {

struct Module {
  meld_jit_compile_fn compile = nullptr;
  meld_jit_release_fn release = nullptr;
};

template <class Fn>
Fn symbol(void* handle, const char* name) {
  return reinterpret_cast<Fn>(dlsym(handle, name));
}

// The module stays loaded for the rest of the process (LLVM does not take well to unloading).
Module loadModule() {
  static const std::string kWhat = "native code module";
#ifdef MELD_JIT_MODULE_BUILD_PATH
  const char* build = MELD_JIT_MODULE_BUILD_PATH;
#else
  const char* build = nullptr;
#endif
  try {
    const std::string path = support::findToolchainModule("MELD_JIT_MODULE", "libmeld_jit.so", build, kWhat);
    void* handle = support::openToolchainModule(path, kWhat);
    auto version = symbol<meld_jit_version_fn>(handle, "meld_jit_version");
    Module m{symbol<meld_jit_compile_fn>(handle, "meld_jit_compile"),
             symbol<meld_jit_release_fn>(handle, "meld_jit_release")};
    if (!version || !m.compile || !m.release)
      throw NativeError(path + " is not a native code module of this toolchain");
    if (version() != MELD_JIT_MODULE_VERSION)
      throw NativeError(path + " is a native code module of another version of this toolchain");
    return m;
  } catch (const NativeError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw NativeError(e.what());
  }
}

}  // namespace

std::unique_ptr<JitCode> JitCode::compile(const meldvm::Program& program, const CompileProgress& progress) {
  const Module module = loadModule();
  auto tell = [](std::size_t done, std::size_t total, void* context) {
    (*static_cast<const CompileProgress*>(context))(done, total);
  };
  meld_jit_result result{};
  char error[1024] = "";
  if (module.compile(&program, progress ? +tell : nullptr, const_cast<CompileProgress*>(&progress), &result,
                     error, sizeof error) != 0)
    throw NativeError(error);
  std::unique_ptr<JitCode> code(new JitCode());
  code->release_ = module.release;
  code->owner_ = result.owner;
  code->entries_.assign(result.entries, result.entries + result.count);
  return code;
}

JitCode::~JitCode() {
  if (release_) release_(owner_);
}

}  // namespace meldc::native
