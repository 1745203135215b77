// Loading a block program from a shared object (a C BlockCode, natively compiled Meld): dlopen the
// file, find `vs_blockcode_entry`, check the ABI version. Every way this can go wrong (missing file,
// not a shared object, no entry symbol, wrong ABI) becomes a BlockCodeError with a message that
// names the file and says what to do — loading never crashes the host.
#pragma once

#include <stdexcept>
#include <string>

#include "simcore/blockcode.h"

namespace simcore {

class BlockCodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class BlockCodeLibrary {
 public:
  // Opens `path` (a path, never searched for in the library path). Throws BlockCodeError.
  static BlockCodeLibrary open(const std::string& path);

  BlockCodeLibrary(BlockCodeLibrary&& other) noexcept;
  BlockCodeLibrary& operator=(BlockCodeLibrary&& other) noexcept;
  BlockCodeLibrary(const BlockCodeLibrary&) = delete;
  BlockCodeLibrary& operator=(const BlockCodeLibrary&) = delete;
  // Unloads the object: the code table must no longer be in use (destroy the Simulation first).
  ~BlockCodeLibrary();

  // The block program's table; valid while this object lives.
  const vs_blockcode* code() const { return code_; }
  // The program's own name, or the file name when the table has none.
  std::string name() const;
  const std::string& path() const { return path_; }

 private:
  BlockCodeLibrary(void* handle, const vs_blockcode* code, std::string path)
      : handle_(handle), code_(code), path_(std::move(path)) {}

  void* handle_ = nullptr;
  const vs_blockcode* code_ = nullptr;
  std::string path_;
};

}  // namespace simcore
