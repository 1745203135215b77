#include "meldc/jit_loader.hpp"

#include <string>

#include "support/toolchain_module.hpp"

namespace meldc::native {

namespace {

struct Module {
  meld_jit_compile_fn compile = nullptr;
  meld_jit_release_fn release = nullptr;
};

// The module stays loaded for the rest of the process (LLVM does not take well to unloading).
Module loadModule() {
  const std::string what = "native code module";
  try {
    const std::string path =
        support::findToolchainModule("MELD_JIT_MODULE", "libmeld_jit.so", MELD_JIT_MODULE_BUILD_PATH, what);
    void* handle = support::openToolchainModule(path, what, "meld_jit_version", MELD_JIT_MODULE_VERSION,
                                                {"meld_jit_compile", "meld_jit_release"});
    return {support::moduleFunction<meld_jit_compile_fn>(handle, "meld_jit_compile"),
            support::moduleFunction<meld_jit_release_fn>(handle, "meld_jit_release")};
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
