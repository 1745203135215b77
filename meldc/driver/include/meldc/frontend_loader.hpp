// Meld source compiled by the module libmeld_frontend.so (frontend_module.h), loaded on the first
// compilation: a `meld` that runs bytecode or native code never loads the ANTLR runtime nor builds
// the parser's tables. Needs none of meldc's libraries.
#pragma once

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "meldvm/program.hpp"

namespace meldc {

// The module is missing, foreign or of another build.
class FrontEndModuleError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// The compiled program fails the VM's verifier (a bug of the compiler), or the compiler failed.
class FrontEndInternalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// compileProgram (compile.hpp) through the module: the -I folders, then the standard library;
// -D NAME=VALUE pairs. nullptr when the program has errors; the diagnostics go to `diagnostics`.
// The module is $MELD_FRONTEND_MODULE when that is set, else <bin>/../lib/meld/libmeld_frontend.so
// (an installation), else this build tree's.
std::unique_ptr<meldvm::Program> compileThroughModule(
    const std::string& path, const std::vector<std::string>& includeDirs,
    const std::vector<std::pair<std::string, std::string>>& defines, std::ostream& diagnostics);

}  // namespace meldc
