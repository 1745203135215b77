#include "jit_compiler.hpp"

#include "meldc/compile_progress_line.hpp"
#include "meldc/jit_loader.hpp"

namespace vsim {

void JitCompiler::compile(MeldCode& code) const {
  std::shared_ptr<meldc::native::JitCode> jit;
  try {
    meldc::CompileProgressLine progress("vsim", showProgress_);
    jit = meldc::native::JitCode::compile(
        code.program(), [&](std::size_t done, std::size_t total) { progress.update(done, total); });
  } catch (const meldc::native::NativeError& e) {
    throw ProgramLoadError(std::string("native code: ") + e.what());
  }
  code.jitCode = std::make_unique<meldvm::NativeCode>(code.program(), jit->entries());
  code.jit = jit;
}

}  // namespace vsim
