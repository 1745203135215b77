// libFuzzer entry point for `.mbc` files as `meld` meets them: any input must either be refused by
// the reader/verifier (BytecodeError) or load, survive the writer (one encoding per program) and the
// disassembler, and then run on its own graph to an end (quiescence, a RuntimeError, or the step
// limit); anything else (a crash, a sanitizer report, a trap, a hang) is a bug. Read in place
// (readBytecodeInPlace, as meld reads a file), the same input must give the same program or error.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "axiom_order.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/bytecode_internal.hpp"
#include "run_bounded.hpp"

namespace {

// The reader's answer: the program's listing, or its error.
std::string readingOf(const std::unique_ptr<meldvm::Program>& program, const std::string& error) {
  if (!program) return "error: " + error;
  std::ostringstream text;
  meldvm::disassemble(*program, text);
  return text.str();
}

// Read in place (as meld reads a file: literal axioms left in the bytes), the same bytes give the
// same program or the same error as read copied.
void checkInPlace(const std::uint8_t* data, std::size_t size) {
  std::unique_ptr<meldvm::Program> copied, inPlace;
  std::string copiedError, inPlaceError;
  try {
    copied = meldvm::readBytecode(data, size);
  } catch (const meldvm::BytecodeError& e) {
    copiedError = e.what();
  }
  std::vector<std::uint32_t> words((size + 3) / 4);  // aligned, as a file's mapping is
  if (size) std::memcpy(words.data(), data, size);
  try {
    inPlace = meldvm::readBytecodeInPlace(reinterpret_cast<const std::uint8_t*>(words.data()), size, nullptr);
  } catch (const meldvm::BytecodeError& e) {
    inPlaceError = e.what();
  }
  if (readingOf(copied, copiedError) != readingOf(inPlace, inPlaceError)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  checkInPlace(data, size);
  const std::unique_ptr<meldvm::Program> program = meldfuzz::readOrNull(data, size);
  if (!program) return 0;
  // What loads must be what the writer writes: the format has one encoding (an older version's
  // file is written back as the current version: its version word, its section count and an
  // empty sources section differ, all at fixed places), but for the order of the axiom blocks,
  // which files of earlier meldc builds have otherwise (axiom_order.hpp).
  auto again = meldvm::writeBytecode(*program);
  std::uint32_t version = 0;
  std::memcpy(&version, data + 4, 4);
  if (version < 3) {
    const std::size_t sources = 8 + 4 + 4 * meldvm::detail::codeBlockCount(*program);
    if (again.size() != size + sources) __builtin_trap();
    again.resize(size);
  }
  if (version < meldvm::kBytecodeVersion && again.size() == size)
    std::copy(data + 4, data + 12, again.begin() + 4);
  // (Or the file holds axiom blocks of literal facts before the others: axiom_order.hpp.)
  if ((again.size() != size || !std::equal(again.begin(), again.end(), data)) &&
      !meldfuzz::sameButAxiomOrder(
          {data, size}, again,
          1 + program->functions.size() + program->rules.size() + program->processes.size()))
    __builtin_trap();
  std::ostringstream text;
  meldvm::disassemble(*program, text);
  meldfuzz::runBounded(*program, text);
  return 0;
}
