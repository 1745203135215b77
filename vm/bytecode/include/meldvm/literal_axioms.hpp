// Axiom blocks that hold only literal facts: AXIOM_FACTS instructions and a RET, no registers and
// no slots. meldc makes one of these for each node of a data file, and the reader keeps them apart
// from the CodeBlocks, in one of two ways:
// - copied, back to back in a few arrays (as CodeBlocks they took three allocations each: code,
//   source lines, label; pagerank-movies has 7,967 such blocks);
// - viewed (readBytecodeFile): left where they are in the file's mapping, which this object keeps
//   alive. A data file's facts are most of its bytes, and copying them was about a third of
//   pagerank-movies' page faults (which cost 5 to 15 us each on the project's VMs).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meldvm/source_line.hpp"

namespace meldvm {

struct CodeBlock;

class LiteralAxioms {
 public:
  std::size_t size() const { return blocks_.size(); }
  bool empty() const { return blocks_.empty(); }

  // Copied blocks. add appends block size() with this code and label; its source lines are
  // appended later, by addLines, in block order.
  void add(std::span<const std::uint32_t> code, std::string_view label);
  // The source lines of the next block that has none yet (blocks without lines: an empty span).
  void addLines(std::span<const SourceLine> lines);
  // For the reader: makes room for `blocks` more blocks (a bound: the file's axiom blocks).
  void reserveBlocks(std::size_t blocks) { blocks_.reserve(blocks_.size() + blocks); }
  // For the reader: makes room for `words` more code words.
  void reserveCode(std::size_t words) { words_.reserve(words_.size() + words); }
  // For the reader: makes room for `lines` more source lines (a bound: the pages of the room
  // not used are never touched, while growing by doubling copied the lines and faulted in about
  // twice their size).
  void reserveLines(std::size_t lines) { words_.reserve(words_.size() + lines * kLineWords); }

  // Viewed blocks: from here on (on an empty object), blocks are runs of `bytes` (4-byte aligned,
  // the host's byte order), which stay valid while `owner` lives (an empty owner: the caller keeps
  // them valid as long as this object). Offsets are in bytes from `bytes`.
  void view(const std::uint8_t* bytes, std::shared_ptr<const void> owner);
  bool viewing() const { return view_ != nullptr; }
  void addViewed(std::size_t codeAt, std::uint32_t codeWords, std::size_t labelAt, std::uint32_t labelBytes);
  void addLinesViewed(std::size_t linesAt, std::uint32_t lineCount);

  std::span<const std::uint32_t> code(std::size_t i) const {
    const Block& b = blocks_[i];
    return {reinterpret_cast<const std::uint32_t*>(base() + b.code), b.codeWords};
  }
  std::string_view label(std::size_t i) const {
    const Block& b = blocks_[i];
    return {reinterpret_cast<const char*>(base() + b.label), b.labelBytes};
  }
  std::span<const SourceLine> lines(std::size_t i) const {
    if (i >= linesAdded_) return {};
    const Block& b = blocks_[i];
    return {reinterpret_cast<const SourceLine*>(base() + b.lines), b.lineCount};
  }
  // Block i as a CodeBlock of its own (a copy: for the writer's tests and the disassembler).
  CodeBlock block(std::size_t i) const;

 private:
  static constexpr std::size_t kLineWords = sizeof(SourceLine) / 4;
  struct Block {
    std::uint64_t code = 0, label = 0, lines = 0;  // byte offsets from base()
    std::uint32_t codeWords = 0, labelBytes = 0, lineCount = 0;
  };
  const std::uint8_t* base() const {
    return view_ ? view_ : reinterpret_cast<const std::uint8_t*>(words_.data());
  }
  void checkMode(bool viewed) const;
  void pushBlock(const Block& b);

  std::vector<Block> blocks_;
  std::size_t linesAdded_ = 0;        // blocks whose lines were added (a prefix)
  std::vector<std::uint32_t> words_;  // copied blocks: labels (padded to words), code, lines
  const std::uint8_t* view_ = nullptr;
  std::shared_ptr<const void> owner_;
};

}  // namespace meldvm
