// Fuzz entry point for Meld source as `meld prog.meld` meets it: any text must either be refused
// with diagnostics or compile to bytecode that passes the verifier, and then run on its own graph
// to an end (quiescence, a RuntimeError, or the step limit). A crash, a sanitizer report, a hang or
// an internal compiler error (bytecode the verifier refuses) is a bug. So is any difference, in
// messages or bytecode, between the compact path of ground facts and the parser's (every fact an
// ast::Rule): the compact path must be invisible.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "meldc/compile.hpp"
#include "meldvm/bytecode.hpp"
#include "run_bounded.hpp"

namespace {

struct Compiled {
  std::string messages;
  std::vector<std::uint8_t> bytecode;
  std::unique_ptr<meldvm::Program> program;
};

Compiled compile(const std::string& path, bool groundFacts) {
  meldc::SourceManager sources;
  std::ostringstream messages;
  meldc::Diagnostics diag(sources, messages);
  Compiled out;
  meldc::FrontEndInput input{path, {}, {}};
  input.groundFacts = groundFacts;
  try {
    out.program = meldc::compileProgram(input, sources, diag);
  } catch (const meldc::InternalCompilerError&) {
    __builtin_trap();
  }
  out.messages = messages.str();
  if (out.program) out.bytecode = meldvm::writeBytecode(*out.program);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The front end reads files (includes are resolved next to them): one scratch file per process.
  static const std::string path = "/tmp/meld-fuzz-" + std::to_string(::getpid()) + ".meld";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  Compiled compact = compile(path, true);
  const Compiled plain = compile(path, false);
  if (compact.messages != plain.messages || compact.bytecode != plain.bytecode) __builtin_trap();
  std::ostringstream messages;
  if (compact.program) meldfuzz::runBounded(*compact.program, messages);
  return 0;
}
