#include "meldc/jit_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/program_dir.hpp"

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

// The module stays loaded for the rest of the process (LLVM does not take well to unloading); a
// second dlopen of the same file returns the same handle.
Module openModule(const std::string& path) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw NativeError("cannot load the native code module " + path + ": " + dlerror());
  auto version = symbol<meld_jit_version_fn>(handle, "meld_jit_version");
  Module m{symbol<meld_jit_compile_fn>(handle, "meld_jit_compile"),
           symbol<meld_jit_release_fn>(handle, "meld_jit_release")};
  if (!version || !m.compile || !m.release)
    throw NativeError(path + " is not a native code module of this toolchain");
  if (version() != MELD_JIT_MODULE_VERSION)
    throw NativeError(path + " is a native code module of another version of this toolchain");
  return m;
}

Module loadModule() {
  if (const char* named = std::getenv("MELD_JIT_MODULE"); named && *named) {
    if (!std::filesystem::exists(named))
      throw NativeError(std::string("MELD_JIT_MODULE names ") + named + ", which does not exist");
    return openModule(named);
  }
  std::vector<std::string> places;
  if (const std::filesystem::path bin = support::runningProgramDir(); !bin.empty())
    places.push_back((bin.parent_path() / "lib" / "meld" / "libmeld_jit.so").string());
#ifdef MELD_JIT_MODULE_BUILD_PATH
  places.push_back(MELD_JIT_MODULE_BUILD_PATH);
#endif
  std::string tried;
  for (const std::string& place : places) {
    if (std::filesystem::exists(place)) return openModule(place);
    tried += "\n  " + place;
  }
  throw NativeError("the native code module libmeld_jit.so is not installed (looked for" + tried + ")");
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
