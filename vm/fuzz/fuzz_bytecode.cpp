// libFuzzer entry point for the `.mbc` reader: any input must either load (and then survive the
// writer and the disassembler) or raise BytecodeError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "meldvm/bytecode.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto program = meldvm::readBytecode(data, size);
    // What loads must be what the writer writes: the format has exactly one encoding.
    const auto again = meldvm::writeBytecode(*program);
    if (again.size() != size || !std::equal(again.begin(), again.end(), data)) __builtin_trap();
    std::ostringstream listing;
    meldvm::disassemble(*program, listing);
  } catch (const meldvm::BytecodeError&) {
  }
  return 0;
}
