// Fuzz entry point for the native backend, fed with `.mbc` files: every input that the reader and
// verifier accept must compile to native code (the JIT), and that code must run to the same end as
// the interpreter (the same write-string output and dump, or the same run-time error, under the
// same step limit). Anything else (a refused module, a crash, another result) is a bug.
#include <cstddef>
#include <cstdint>
#include <regex>
#include <sstream>
#include <string>

#include "meldc/native.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/native_code.hpp"
#include "run_bounded.hpp"

namespace {
// How deep a runaway recursion got before the stack budget ran out depends on the frames' size,
// which differs between native and interpreted code (as between builds): the count is left out.
std::string withoutDepth(const std::string& text) {
  static const std::regex depth("nested [0-9]+ calls deep");
  return std::regex_replace(text, depth, "nested N calls deep");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::unique_ptr<meldvm::Program> program = meldfuzz::readOrNull(data, size);
  if (!program) return 0;
  std::unique_ptr<meldc::native::Jit> jit;
  try {
    jit = meldc::native::Jit::compile(*program);
  } catch (const meldc::native::NativeError&) {
    __builtin_trap();  // verified bytecode always has native code
  }
  const meldvm::NativeCode native(*program, jit->entries());
  std::ostringstream interpreted, compiled;
  meldfuzz::runBounded(*program, interpreted);
  meldfuzz::runBounded(*program, compiled, &native);
  if (withoutDepth(interpreted.str()) != withoutDepth(compiled.str())) __builtin_trap();
  return 0;
}
