#include "meldvm/native_library.hpp"

#include <dlfcn.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>

#include "meldvm/bytecode.hpp"

namespace meldvm {

namespace {
BytecodeError bad(const std::string& path, const std::string& what) {
  return BytecodeError(path + ": " + what, 0);
}
}  // namespace

std::unique_ptr<NativeLibrary> NativeLibrary::open(const std::string& path) {
  std::unique_ptr<NativeLibrary> lib(new NativeLibrary());
  // A path without a slash would be searched for on the library path: name the file itself.
  const std::string file = path.find('/') == std::string::npos ? "./" + path : path;
  lib->handle_ = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!lib->handle_) {
    const char* why = dlerror();
    throw bad(path, std::string("cannot load the shared object: ") + (why ? why : "unknown reason"));
  }
  const auto entry = reinterpret_cast<meld_native_entry>(dlsym(lib->handle_, MELD_NATIVE_ENTRY));
  if (!entry)
    throw bad(path,
              "not a native Meld program (no " MELD_NATIVE_ENTRY "; build one with meldc --emit=native)");
  const meld_native_program_desc* d = entry();
  if (!d || d->magic != MELD_NATIVE_MAGIC) throw bad(path, "not a native Meld program (bad description)");
  if (d->abi_version != MELD_NATIVE_ABI_VERSION)
    throw bad(path, "built for native ABI version " + std::to_string(d->abi_version) +
                        ", this VM runs version " + std::to_string(MELD_NATIVE_ABI_VERSION) +
                        ": compile the program again with this meldc");
  if (d->bytecode_version != kBytecodeVersion)
    throw bad(path, "built for bytecode version " + std::to_string(d->bytecode_version) +
                        ", this VM reads version " + std::to_string(kBytecodeVersion) +
                        ": compile the program again with this meldc");
  try {
    // In place: the library stays open until program_ is gone (~NativeLibrary).
    lib->program_ = readBytecodeInPlace(d->bytecode, std::size_t(d->bytecode_size), nullptr);
  } catch (const BytecodeError& e) {
    throw bad(path, std::string("its bytecode is bad: ") + e.what());
  }
  const std::size_t blocks = nativeCodeBlocks(*lib->program_).size();
  if (d->block_count != blocks || !d->blocks)
    throw bad(path, "has " + std::to_string(d->block_count) + " native blocks for a program of " +
                        std::to_string(blocks));
  const std::span<const meld_native_block> entries(d->blocks, blocks);
  for (std::size_t k = 0; k < blocks; ++k)
    if (!entries[k]) throw bad(path, "native block " + std::to_string(k) + " is missing");
  lib->code_ = std::make_unique<NativeCode>(*lib->program_, entries);
  return lib;
}

NativeLibrary::~NativeLibrary() {
  code_.reset();
  program_.reset();
  if (handle_) dlclose(handle_);
}

bool isNativeProgramFile(const std::string& path) {
  if (path.size() >= 3 && path.compare(path.size() - 3, 3, ".so") == 0) return true;
  // Only a regular file can be loaded as a shared object; the head of a pipe is not read here,
  // or the bytecode reader would miss it.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  static constexpr char kElf[4] = {0x7f, 'E', 'L', 'F'};
  std::ifstream in(path, std::ios::binary);
  char head[4] = {};
  return in.read(head, 4) && std::memcmp(head, kElf, 4) == 0;
}

}  // namespace meldvm
