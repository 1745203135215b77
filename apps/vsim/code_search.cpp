#include "code_search.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "support/program_dir.hpp"

namespace vsim {

namespace fs = std::filesystem;

bool isBareName(const std::string& path) { return !path.empty() && path.find('/') == std::string::npos; }

std::vector<std::string> codeSearchPath(const std::string& firstDir) {
  std::vector<std::string> dirs{firstDir.empty() ? std::string(".") : firstDir};
  if (const char* env = std::getenv("VSIM_CODE_PATH")) {
    std::string list = env;
    for (std::size_t start = 0; start <= list.size();) {
      const std::size_t colon = std::min(list.find(':', start), list.size());
      if (colon > start) dirs.push_back(list.substr(start, colon - start));
      start = colon + 1;
    }
  }
  if (const fs::path here = support::runningProgramDir(); !here.empty())
    for (const char* relative : {"../lib/meld/blockcodes", "../blockcodes", "../../blockcodes"})
      dirs.push_back((here / relative).lexically_normal().string());
  return dirs;
}

std::optional<std::string> findBlockCode(const std::string& name, const std::vector<std::string>& dirs) {
  for (const std::string& dir : dirs) {
    const fs::path candidate = fs::path(dir) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal().string();
  }
  return std::nullopt;
}

}  // namespace vsim
