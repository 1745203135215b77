#include "simcore/blockcode_library.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <utility>

namespace simcore {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw BlockCodeError("block code '" + path + "': " + why);
}

// dlopen's own messages for a wrong file are cryptic ("invalid ELF header"); checking the file
// first gives the user an answer in their terms.
void checkFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail(path, "is a directory, not a shared object");
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  if (!in || !in.read(magic, 4)) {
    if (!in.is_open()) fail(path, "cannot be read");
    fail(path, "is not a shared object (file too short)");
  }
  if (std::memcmp(magic,
                  "\x7f"
                  "ELF",
                  4) != 0)
    fail(path,
         "is not a shared object (no ELF header); build a C BlockCode with "
         "`cc -shared -fPIC -I simcore/include prog.c -o prog.so`");
}

}  // namespace

BlockCodeLibrary BlockCodeLibrary::open(const std::string& path) {
  if (path.empty()) throw BlockCodeError("block code: empty file name");
  checkFile(path);
  // Without a slash dlopen would search the library path instead of opening the file named.
  const std::string loadPath = path.find('/') == std::string::npos ? "./" + path : path;
  dlerror();
  void* handle = ::dlopen(loadPath.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* err = dlerror();
    fail(path, std::string("cannot be loaded: ") + (err ? err : "unknown dlopen error"));
  }
  // From here on the handle must be closed on every error path.
  auto closeAndFail = [&](const std::string& why) {
    ::dlclose(handle);
    fail(path, why);
  };
  dlerror();
  void* symbol = ::dlsym(handle, VS_BLOCKCODE_ENTRY_SYMBOL);
  if (!symbol)
    closeAndFail("does not export `" VS_BLOCKCODE_ENTRY_SYMBOL
                 "` (a block program defines `const vs_blockcode *vs_blockcode_entry(void)`, see "
                 "simcore/include/simcore/blockcode.h)");
  vs_blockcode_entry_fn entry;
  static_assert(sizeof entry == sizeof symbol);
  std::memcpy(&entry, &symbol, sizeof entry);  // object -> function pointer, as POSIX allows
  const vs_blockcode* code = entry();
  if (!code) closeAndFail("`" VS_BLOCKCODE_ENTRY_SYMBOL "` returned no block program (NULL)");
  if (!vs_abi_supported(code->abi_version))
    closeAndFail("was built for block ABI version " + std::to_string(code->abi_version) +
                 ", this simulator speaks versions " + std::to_string(VS_ABI_OLDEST_VERSION) + " to " +
                 std::to_string(VS_ABI_VERSION) + "; rebuild it against this simcore/include/simcore/blockcode.h");
  return BlockCodeLibrary(handle, code, path);
}

BlockCodeLibrary::BlockCodeLibrary(BlockCodeLibrary&& other) noexcept
    : handle_(std::exchange(other.handle_, nullptr)),
      code_(std::exchange(other.code_, nullptr)),
      path_(std::move(other.path_)) {}

BlockCodeLibrary& BlockCodeLibrary::operator=(BlockCodeLibrary&& other) noexcept {
  if (this != &other) {
    if (handle_) ::dlclose(handle_);
    handle_ = std::exchange(other.handle_, nullptr);
    code_ = std::exchange(other.code_, nullptr);
    path_ = std::move(other.path_);
  }
  return *this;
}

BlockCodeLibrary::~BlockCodeLibrary() {
  if (handle_) ::dlclose(handle_);
}

std::string BlockCodeLibrary::name() const {
  if (code_ && code_->name && *code_->name) return code_->name;
  const auto slash = path_.rfind('/');
  return slash == std::string::npos ? path_ : path_.substr(slash + 1);
}

}  // namespace simcore
