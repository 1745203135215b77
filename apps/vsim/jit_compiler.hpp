// vsim --jit: the LLVM backend behind vsim_session's NativeCompiler, in the module libmeld_jit.so that
// vsim loads on the first --jit compile (meldc/jit_loader.hpp), never for bytecode.
#pragma once

#include "meld_program.hpp"

namespace vsim {

class JitCompiler final : public NativeCompiler {
 public:
  // `showProgress`: the progress line of a compile longer than a second (meldc/compile_progress_line.hpp).
  explicit JitCompiler(bool showProgress) : showProgress_(showProgress) {}
  void compile(MeldCode& code) const override;  // throws ProgramLoadError

 private:
  bool showProgress_;
};

}  // namespace vsim
