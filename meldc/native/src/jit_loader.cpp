#include "meldc/jit_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

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
Module loadModule() {
  std::string tried;
  const bool named = std::getenv("MELD_JIT_MODULE") && *std::getenv("MELD_JIT_MODULE");
  for (const std::string& place : JitCode::modulePlaces()) {
    if (!std::filesystem::exists(place)) {
      if (named) throw JitError("MELD_JIT_MODULE names " + place + ", which does not exist");
      tried += "\n  " + place;
      continue;
    }
    void* handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw JitError("cannot load the native code module " + place + ": " + dlerror());
    auto version = symbol<meld_jit_version_fn>(handle, "meld_jit_version");
    Module m{symbol<meld_jit_compile_fn>(handle, "meld_jit_compile"),
             symbol<meld_jit_release_fn>(handle, "meld_jit_release")};
    if (!version || !m.compile || !m.release)
      throw JitError(place + " is not a native code module of this toolchain");
    if (version() != MELD_JIT_MODULE_VERSION)
      throw JitError(place + " is a native code module of another version of this toolchain");
    return m;
  }
  throw JitError("the native code module libmeld_jit.so is not installed (looked for" + tried + ")");
}

}  // namespace

std::vector<std::string> JitCode::modulePlaces() {
  std::vector<std::string> places;
  if (const char* env = std::getenv("MELD_JIT_MODULE"); env && *env) places.push_back(env);
  if (const std::filesystem::path bin = support::runningProgramDir(); !bin.empty())
    places.push_back((bin.parent_path() / "lib" / "meld" / "libmeld_jit.so").string());
#ifdef MELD_JIT_MODULE_BUILD_PATH
  places.push_back(MELD_JIT_MODULE_BUILD_PATH);
#endif
  return places;
}

std::unique_ptr<JitCode> JitCode::compile(const meldvm::Program& program, const Progress& progress) {
  const Module module = loadModule();
  auto tell = [](std::size_t done, std::size_t total, void* context) {
    (*static_cast<const Progress*>(context))(done, total);
  };
  meld_jit_result result{};
  char error[1024] = "";
  if (module.compile(&program, progress ? +tell : nullptr, const_cast<Progress*>(&progress), &result, error,
                     sizeof error) != 0)
    throw JitError(error);
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
