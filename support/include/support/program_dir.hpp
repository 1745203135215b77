// The folder of the running program, for data found relative to it (an installation's
// <prefix>/bin next to <prefix>/share and <prefix>/lib, or a build tree's layout): meldc's standard
// library and vsim's BlockCodes. Linux: /proc/self/exe; an empty path where that is unknown.
#pragma once

#include <filesystem>
#include <system_error>

namespace support {

inline std::filesystem::path runningProgramDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

}  // namespace support
