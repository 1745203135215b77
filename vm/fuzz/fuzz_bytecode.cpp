// libFuzzer entry point for `.mbc` files as `meld` meets them: any input must either be refused by
// the reader/verifier (BytecodeError) or load, survive the writer (one encoding per program) and the
// disassembler, and then run on its own graph to an end (quiescence, a RuntimeError, or the step
// limit); anything else (a crash, a sanitizer report, a trap, a hang) is a bug.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "meldvm/bytecode.hpp"
#include "run_bounded.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::unique_ptr<meldvm::Program> program;
  try {
    program = meldvm::readBytecode(data, size);
  } catch (const meldvm::BytecodeError&) {
    return 0;
  }
  // What loads must be what the writer writes: the format has exactly one encoding (the version
  // word aside: an older version's file is written back as the current version).
  auto again = meldvm::writeBytecode(*program);
  if (again.size() != size) __builtin_trap();
  std::copy(data + 4, data + 8, again.begin() + 4);
  if (!std::equal(again.begin(), again.end(), data)) __builtin_trap();
  std::ostringstream text;
  meldvm::disassemble(*program, text);
  meldfuzz::runBounded(*program, text);
  return 0;
}
