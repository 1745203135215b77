// Fuzz entry point for Meld source as `meld prog.meld` meets it: any text must either be refused
// with diagnostics or compile to bytecode that passes the verifier, and then run on its own graph
// to an end (quiescence, a RuntimeError, or the step limit). A crash, a sanitizer report, a hang or
// an internal compiler error (bytecode the verifier refuses) is a bug.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "meldc/compile.hpp"
#include "run_bounded.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The front end reads files (includes are resolved next to them): one scratch file per process.
  static const std::string path = "/tmp/meld-fuzz-" + std::to_string(::getpid()) + ".meld";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  meldc::SourceManager sources;
  std::ostringstream messages;
  meldc::Diagnostics diag(sources, messages);
  std::unique_ptr<meldvm::Program> program;
  try {
    program = meldc::compileProgram({path, {}, {}}, sources, diag);
  } catch (const meldc::InternalCompilerError&) {
    __builtin_trap();
  }
  if (program) meldfuzz::runBounded(*program, messages);
  return 0;
}
