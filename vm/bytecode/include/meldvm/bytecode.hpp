// The `.mbc` file format: a versioned, little-endian serialisation of a Program (program.hpp).
// Layout (all integers 32-bit little-endian unless said otherwise; strings = length + bytes padded
// to 4):
//   magic "MBC1", version (kBytecodeVersion), section count, then sections in this order:
//   types, predicates, nodes, strings, globals, functions, externs, rules, processes, axioms,
//   scheduling, indexes, and from version 3 on sources (the source files and, per code block in
//   the order globals, functions, rules, processes, axioms, its source lines). Each section = tag word, byte
//   length, payload. A code block = label, register count + register types, slot count, word count + words.
// The loader checks everything before the VM runs any of it (verifyProgram): counts and bounds,
// operand kinds and register types of every instruction against opcodes.def, jump targets on
// instruction boundaries, loop nesting, slots. Malformed input gives a BytecodeError, never a crash.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "meldvm/program.hpp"

namespace meldvm {

// Version 2 added RET_IF_UPDATED (a merged rule stops after an in-place update) and the
// scheduling flag of `priority @no_priority`; version 3 the sources section (file:line of rules
// and axioms, for derivation trees); version 4 AXIOM_FACTS (constant axioms as data words).
// Every change so far only adds: the reader also takes version 1 to 3 files, and an older VM
// refuses a newer file by its version.
inline constexpr std::uint32_t kBytecodeVersion = 4;
inline constexpr std::uint32_t kOldestBytecodeVersion = 1;

class BytecodeError : public std::runtime_error {
 public:
  // `offset`: byte offset in the file where the problem was found (or 0).
  BytecodeError(const std::string& what, std::size_t offset) : std::runtime_error(what), offset_(offset) {}
  std::size_t offset() const { return offset_; }

 private:
  std::size_t offset_;
};

std::vector<std::uint8_t> writeBytecode(const Program& program);
// Parses and verifies; throws BytecodeError.
std::unique_ptr<Program> readBytecode(const std::uint8_t* data, std::size_t size);
// As readBytecode, but the program's literal axioms (a data file's facts, most of a big file) are
// read where they lie in `data` instead of being copied: `data` must stay unchanged while the
// program lives, and the program keeps `owner` (which may keep `data` alive; may be empty).
std::unique_ptr<Program> readBytecodeInPlace(const std::uint8_t* data, std::size_t size,
                                             std::shared_ptr<const void> owner);
// Reads the file in place: the program keeps the file's mapping (see file_bytes.hpp).
std::unique_ptr<Program> readBytecodeFile(const std::string& path);  // also BytecodeError for I/O

// Checks every code block of a program built in memory (also run by readBytecode); throws
// BytecodeError naming the block and the instruction.
void verifyProgram(const Program& program);

// Human-readable listing (meldc --emit=asm): predicates, nodes, then every code block, one
// instruction per line with its operands named by kind.
void disassemble(const Program& program, std::ostream& out);

}  // namespace meldvm
