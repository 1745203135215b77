// A native Meld program (`meldc --emit=native`) loaded from a shared object: its bytecode, read and
// verified like a .mbc file, and the native entry of each block (native_abi.h). The code stays
// loaded as long as the NativeLibrary lives.
#pragma once

#include <memory>
#include <string>

#include "meldvm/native_code.hpp"
#include "meldvm/program.hpp"

namespace meldvm {

class NativeLibrary {
 public:
  // Throws BytecodeError saying what is wrong: the file cannot be loaded, it is not a native Meld
  // program, it was built for another native ABI or bytecode version, its bytecode is bad.
  static std::unique_ptr<NativeLibrary> open(const std::string& path);
  ~NativeLibrary();
  NativeLibrary(const NativeLibrary&) = delete;
  NativeLibrary& operator=(const NativeLibrary&) = delete;

  const Program& program() const { return *program_; }
  const NativeCode& code() const { return *code_; }

 private:
  NativeLibrary() = default;
  void* handle_ = nullptr;
  std::unique_ptr<Program> program_;
  std::unique_ptr<NativeCode> code_;
};

// Whether the program file is a shared object to open as a NativeLibrary: a `.so` name, or a file
// that starts like an ELF object (meld and vsim tell .meld/.mbc programs from native ones so).
bool isNativeProgramFile(const std::string& path);

}  // namespace meldvm
