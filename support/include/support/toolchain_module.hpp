// The modules a program of this toolchain loads only when it needs them (libmeld_jit.so for --jit,
// libmeld_frontend.so for meld FILE.meld): where each one is, opening it, and the error text of
// their C seams. Linux (dlopen); link ${CMAKE_DL_LIBS}.
#pragma once

#include <dlfcn.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/program_dir.hpp"

namespace support {

// The file $envVariable names when it is set (it must exist), else <bin>/../lib/meld/<file> (an
// installation), else `buildPath` (this build tree's, or null). Throws std::runtime_error naming
// `what` and the places it looked in.
inline std::string findToolchainModule(const char* envVariable, const char* file, const char* buildPath,
                                       const std::string& what) {
  if (const char* named = std::getenv(envVariable); named && *named) {
    if (!std::filesystem::exists(named))
      throw std::runtime_error(std::string(envVariable) + " names " + named + ", which does not exist");
    return named;
  }
  std::vector<std::string> places;
  if (const std::filesystem::path bin = runningProgramDir(); !bin.empty())
    places.push_back((bin.parent_path() / "lib" / "meld" / file).string());
  if (buildPath) places.emplace_back(buildPath);
  std::string tried;
  for (const std::string& place : places) {
    if (std::filesystem::exists(place)) return place;
    tried += "\n  " + place;
  }
  throw std::runtime_error("the " + what + " " + file + " is not installed (looked for" + tried + ")");
}

// Opens it for good (RTLD_NOW | RTLD_LOCAL; a second open of the same file gives the same handle)
// and checks that it is a module of this toolchain and build: it has every one of `symbols`, and
// the function `versionSymbol` returns `version`. Throws std::runtime_error naming `what`.
inline void* openToolchainModule(const std::string& path, const std::string& what, const char* versionSymbol,
                                 int version, std::initializer_list<const char*> symbols) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error("cannot load the " + what + " " + path + ": " + dlerror());
  const auto versionOf = reinterpret_cast<int (*)()>(dlsym(handle, versionSymbol));
  bool complete = versionOf != nullptr;
  for (const char* name : symbols) complete = complete && dlsym(handle, name) != nullptr;
  if (!complete) throw std::runtime_error(path + " is not a " + what + " of this toolchain");
  if (versionOf() != version)
    throw std::runtime_error(path + " is a " + what + " of another version of this toolchain");
  return handle;
}

// A function of an opened module (openToolchainModule checked that it is there).
template <class Fn>
Fn moduleFunction(void* handle, const char* name) {
  return reinterpret_cast<Fn>(dlsym(handle, name));
}

// A message into a C seam's error buffer of `size` bytes: cut to fit, NUL-terminated.
inline void copyModuleMessage(const char* message, char* out, std::size_t size) {
  if (size == 0) return;
  std::strncpy(out, message, size - 1);
  out[size - 1] = '\0';
}

}  // namespace support
