// Include merging (§4.8): reads the main file, follows `include #path` (relative to the including
// file, then each -I directory), parses every file once and merges the ASTs: the including file's
// items first, then its included files in reverse order of inclusion (recursively).
// A file included a second time is skipped; an include cycle and a missing file are errors at the
// include line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"

namespace meldc {

// Returns nullopt only when the main file cannot be read or parsed at all; otherwise a program
// (possibly missing the parts of broken included files; errors are in `diag`).
std::optional<ast::Program> loadProgram(const std::string& mainPath,
                                        const std::vector<std::string>& includeDirs, SourceManager& sources,
                                        Diagnostics& diag);

}  // namespace meldc
