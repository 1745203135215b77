// Axiom blocks that hold only literal facts: AXIOM_FACTS instructions and a RET, no registers and
// no slots. meldc makes one of these for each node of a data file, and the reader keeps them back
// to back in a few arrays, not as a CodeBlock each. pagerank-movies has 7,967 such blocks, and as
// CodeBlocks they took three allocations each (code, source lines, label).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meldvm/source_line.hpp"

namespace meldvm {

struct CodeBlock;

class LiteralAxioms {
 public:
  std::size_t size() const { return codeStart_.size() - 1; }
  bool empty() const { return size() == 0; }

  // Appends block size() with this code and label. Its source lines are appended later, by
  // addLines, in block order.
  void add(std::span<const std::uint32_t> code, std::string_view label);
  // The source lines of the next block that has none yet (blocks without lines: an empty span).
  void addLines(std::span<const SourceLine> lines);
  // For the reader: makes room for `words` more code words.
  void reserveCode(std::size_t words) { code_.reserve(code_.size() + words); }
  // For the reader: makes room for `lines` more source lines (a bound: the pages of the room
  // not used are never touched, while growing by doubling copied the lines and faulted in about
  // twice their size).
  void reserveLines(std::size_t lines) { lines_.reserve(lines_.size() + lines); }

  std::span<const std::uint32_t> code(std::size_t i) const {
    return {code_.data() + codeStart_[i], codeStart_[i + 1] - codeStart_[i]};
  }
  std::string_view label(std::size_t i) const {
    return std::string_view(labels_).substr(labelStart_[i], labelStart_[i + 1] - labelStart_[i]);
  }
  std::span<const SourceLine> lines(std::size_t i) const {
    if (i + 1 >= lineStart_.size()) return {};
    return {lines_.data() + lineStart_[i], lineStart_[i + 1] - lineStart_[i]};
  }
  // Block i as a CodeBlock of its own (a copy: for the writer's tests and the disassembler).
  CodeBlock block(std::size_t i) const;

 private:
  std::vector<std::uint32_t> code_;
  std::vector<std::size_t> codeStart_{0};  // block i: code_[codeStart_[i], codeStart_[i + 1])
  std::string labels_;
  std::vector<std::size_t> labelStart_{0};
  std::vector<SourceLine> lines_;
  std::vector<std::size_t> lineStart_{0};
};

}  // namespace meldvm
