// The whole pipeline for the drivers that run a program (meld, vsim --program, tests): front end,
// lowering, and the VM's verifier on the result, with the standard library folder searched after
// the -I folders.
#pragma once

#include <memory>
#include <stdexcept>

#include "meldc/diagnostics.hpp"
#include "meldc/frontend.hpp"
#include "meldc/source.hpp"
#include "meldvm/program.hpp"

namespace meldc {

// The compiled program fails the VM's verifier: a bug of the compiler, not of the program.
class InternalCompilerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// nullptr when the program has errors (reported to `diag`); throws InternalCompilerError.
std::unique_ptr<meldvm::Program> compileProgram(FrontEndInput input, SourceManager& sources,
                                                Diagnostics& diag, bool useStdlib = true);

}  // namespace meldc
