// Where a block program named by its file name alone is found (`code="color_flood.so"` in a world,
// `--code color_flood.so`): worlds then run from anywhere, whichever build or installation runs
// them. A name with a folder in it is used as it is (relative to the world file, or to the current
// folder on the command line).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace vsim {

// The folders searched, in order: `firstDir` (the world's folder, or the current one), each folder
// of VSIM_CODE_PATH (colon-separated), then those next to the running program: the installed
// layout's lib/meld/blockcodes and a build tree's blockcodes/ (vsim in build/P/apps/vsim, the IDE in
// build/P/ide).
std::vector<std::string> codeSearchPath(const std::string& firstDir);

// The first `dir/name` that exists in the search path, or nullopt.
std::optional<std::string> findBlockCode(const std::string& name, const std::vector<std::string>& dirs);

// Whether `path` is a bare file name (no folder): such names are searched for.
bool isBareName(const std::string& path);

}  // namespace vsim
