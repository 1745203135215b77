#include "code_builder.hpp"

#include <bit>
#include <stdexcept>

namespace meldc {

Reg CodeBuilder::reg(meldvm::TypeId type) {
  block_.registerTypes.push_back(type);
  return Reg(block_.registerTypes.size() - 1);
}

void CodeBuilder::useSlot(std::uint32_t slot) {
  if (slot + 1 > block_.slots) block_.slots = slot + 1;
}

CodeBuilder::Label CodeBuilder::label() {
  positions_.push_back(kUnplaced);
  return Label(positions_.size() - 1);
}

void CodeBuilder::place(Label l) { positions_.at(l) = std::uint32_t(block_.code.size()); }

CodeBuilder& CodeBuilder::op(meldvm::Opcode o) { return w(std::uint32_t(o)); }

CodeBuilder& CodeBuilder::w(std::uint32_t word) {
  block_.code.push_back(word);
  return *this;
}

CodeBuilder& CodeBuilder::dbl(double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  w(std::uint32_t(bits));
  return w(std::uint32_t(bits >> 32));
}

CodeBuilder& CodeBuilder::to(Label target) {
  patches_.emplace_back(block_.code.size(), target);
  return w(0);
}

CodeBuilder& CodeBuilder::regs(std::span<const Reg> rs) {
  w(std::uint32_t(rs.size()));
  for (Reg r : rs) w(r);
  return *this;
}

void CodeBuilder::emit(meldvm::Opcode o, std::initializer_list<std::uint32_t> words) {
  op(o);
  for (std::uint32_t word : words) w(word);
}

void CodeBuilder::at(std::uint32_t file, std::uint32_t line) {
  const auto pc = std::uint32_t(block_.code.size());
  std::vector<meldvm::SourceLine>& lines = block_.lines;
  if (!lines.empty() && lines.back().file == file && lines.back().line == line) return;
  if (!lines.empty() && lines.back().pc == pc) lines.pop_back();  // nothing came from that one
  if (!lines.empty() && lines.back().file == file && lines.back().line == line) return;
  lines.push_back(meldvm::SourceLine{pc, file, line});
}

meldvm::CodeBlock CodeBuilder::finish(std::string label) {
  // A last entry with no instruction after it says nothing.
  if (!block_.lines.empty() && block_.lines.back().pc >= block_.code.size()) block_.lines.pop_back();
  for (const auto& [at, l] : patches_) {
    if (positions_.at(l) == kUnplaced) throw std::logic_error("meldc: jump to a label never placed");
    block_.code[at] = positions_[l];
  }
  block_.label = std::move(label);
  meldvm::CodeBlock out = std::move(block_);
  block_ = {};
  positions_.clear();
  patches_.clear();
  return out;
}

}  // namespace meldc
