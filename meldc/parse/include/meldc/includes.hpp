// Include merging (§4.8): reads the main file, follows `include #path` (relative to the including
// file, then each -I directory), parses every file once and merges the ASTs: the including file's
// items first, then its included files in reverse order of inclusion (recursively).
// A file included a second time is skipped; an include cycle and a missing file are errors at the
// include line.
// The drivers (meldc, meld, vsim) append defaultStdlibDir() to the -I directories, so that
// `include #blinkyblocks.meld` finds the target files of stdlib/ without any option.
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
// `groundFacts`: as for parseFile (parser.hpp).
std::optional<ast::Program> loadProgram(const std::string& mainPath,
                                        const std::vector<std::string>& includeDirs, SourceManager& sources,
                                        Diagnostics& diag, bool groundFacts = false);

// The standard library folder searched after the -I directories: the value of the environment
// variable MELD_STDLIB when it is set (an empty value means no standard library folder), else an
// installation's <prefix>/share/meld/stdlib when the running program is <prefix>/bin/..., otherwise
// the stdlib/ folder of the source tree, fixed at build time (MELD_STDLIB_DIR). "" when there is
// none. A lookup rather than a constant so that a moved tree or an installed compiler can be
// pointed elsewhere without rebuilding.
std::string defaultStdlibDir();

}  // namespace meldc
