#include "meldvm/literal_axioms.hpp"

#include <cstring>
#include <stdexcept>

#include "meldvm/bytecode_internal.hpp"
#include "meldvm/large_allocator.hpp"
#include "meldvm/program.hpp"

namespace meldvm {

void LiteralAxioms::checkMode(bool viewed) const {
  if (viewing() != viewed)
    throw std::logic_error(viewed ? "meldvm: a viewed literal axiom block added to copied ones"
                                  : "meldvm: a copied literal axiom block added to viewed ones");
}

void LiteralAxioms::add(std::span<const std::uint32_t> code, std::string_view label) {
  checkMode(false);
  Block b;
  b.label = words_.size() * 4;
  b.labelBytes = std::uint32_t(label.size());
  words_.resize(words_.size() + (label.size() + 3) / 4);
  if (!label.empty()) std::memcpy(words_.data() + b.label / 4, label.data(), label.size());
  b.code = words_.size() * 4;
  b.codeWords = std::uint32_t(code.size());
  words_.insert(words_.end(), code.begin(), code.end());
  pushBlock(b);
}

void LiteralAxioms::addLines(std::span<const SourceLine> lines) {
  checkMode(false);
  if (linesAdded_ >= size()) throw std::logic_error("meldvm: source lines for a block not added");
  Block& b = blocks_[linesAdded_++];
  b.lines = words_.size() * 4;
  b.lineCount = std::uint32_t(lines.size());
  words_.resize(words_.size() + lines.size() * kLineWords);
  if (!lines.empty()) std::memcpy(words_.data() + b.lines / 4, lines.data(), lines.size_bytes());
}

void LiteralAxioms::pushBlock(const Block& b) {
  const std::size_t from = blocks_.size() * sizeof(Block);
  blocks_.push_back(b);
  // The room reserveBlocks made is a bound (general blocks take none): prefaulted as it fills.
  support::prefaultAhead(blocks_.data(), blocks_.capacity() * sizeof(Block), from, from + sizeof(Block));
}

void LiteralAxioms::view(const std::uint8_t* bytes, std::shared_ptr<const void> owner) {
  if (!empty() || !words_.empty()) throw std::logic_error("meldvm: viewing bytes after blocks were added");
  view_ = bytes;
  owner_ = std::move(owner);
}

void LiteralAxioms::addViewed(std::size_t codeAt, std::uint32_t codeWords, std::size_t labelAt,
                              std::uint32_t labelBytes) {
  checkMode(true);
  Block b;
  b.code = codeAt;
  b.codeWords = codeWords;
  b.label = labelAt;
  b.labelBytes = labelBytes;
  pushBlock(b);
}

void LiteralAxioms::addLinesViewed(std::size_t linesAt, std::uint32_t lineCount) {
  checkMode(true);
  if (linesAdded_ >= size()) throw std::logic_error("meldvm: source lines for a block not added");
  Block& b = blocks_[linesAdded_++];
  b.lines = linesAt;
  b.lineCount = lineCount;
}

CodeBlock LiteralAxioms::block(std::size_t i) const {
  CodeBlock b;
  b.code.assign(code(i).begin(), code(i).end());
  b.label = label(i);
  b.lines.assign(lines(i).begin(), lines(i).end());
  return b;
}

namespace detail {

bool literalAxiomCode(std::span<const std::uint32_t> code) {
  for (std::size_t pos = 0; pos < code.size();) {
    if (Opcode(code[pos]) == Opcode::RET) return pos + 1 == code.size();
    const std::size_t len = axiomFactsLength(code, pos);
    if (len == 0) return false;
    pos += len;
  }
  return false;  // no RET
}

}  // namespace detail
}  // namespace meldvm
