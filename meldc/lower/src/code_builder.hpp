// Builds one VM code block (program.hpp CodeBlock): instructions with their operand words, labels
// whose J operands are patched when the block is finished, typed registers and fact slots.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "meldvm/program.hpp"

namespace meldc {

using Reg = std::uint32_t;

class CodeBuilder {
 public:
  using Label = std::uint32_t;

  // A new register of the given type (registers are never reused: blocks are small and a fresh
  // register per value keeps the per-register types of the verifier trivially consistent).
  Reg reg(meldvm::TypeId type);
  meldvm::TypeId typeOf(Reg r) const { return block_.registerTypes.at(r); }
  // Slots are numbered by nesting depth: the caller says which depth a loop is at.
  void useSlot(std::uint32_t slot);

  Label label();
  void place(Label l);  // the label denotes the next instruction
  bool placed(Label l) const { return positions_.at(l) != kUnplaced; }

  // Instructions. `op` writes the opcode; the operand helpers append its operands in the order of
  // opcodes.def.
  CodeBuilder& op(meldvm::Opcode o);
  CodeBuilder& w(std::uint32_t word);
  CodeBuilder& imm(std::int32_t value) { return w(std::uint32_t(value)); }
  CodeBuilder& dbl(double value);              // D: two words, low first
  CodeBuilder& to(Label target);               // J
  CodeBuilder& regs(std::span<const Reg> rs);  // *: count, then the registers

  // Shorthand for an instruction whose operands are all plain words.
  void emit(meldvm::Opcode o, std::initializer_list<std::uint32_t> words);

  std::size_t size() const { return block_.code.size(); }
  // The instructions emitted from now on come from this line of the program's source file `file`
  // (an index into meldvm::Program::sourceFiles).
  void at(std::uint32_t file, std::uint32_t line);
  // Patches the jumps and returns the block (the builder is left empty).
  meldvm::CodeBlock finish(std::string label);

 private:
  static constexpr std::uint32_t kUnplaced = 0xFFFFFFFFu;
  meldvm::CodeBlock block_;
  std::vector<std::uint32_t> positions_;
  std::vector<std::pair<std::size_t, Label>> patches_;  // code index of a J operand, its label
};

}  // namespace meldc
