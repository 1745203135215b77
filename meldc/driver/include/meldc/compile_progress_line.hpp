// The progress line meldc, meld and vsim show on a terminal while native code compiles (a large
// program takes seconds to minutes): parts compiled out of all, and the wall time
// (support::TerminalLine: after a second, at most four times a second, in place on stderr, erased
// by finish() or the destructor).
#pragma once

#include <cstddef>
#include <string>
#include <utility>

#include "support/terminal_line.hpp"

namespace meldc {

class CompileProgressLine {
 public:
  // `enabled`: draw at all (the callers pass whether stderr is a terminal, and their --no-progress).
  CompileProgressLine(std::string tool, bool enabled) : tool_(std::move(tool)), line_(enabled) {}
  ~CompileProgressLine() { finish(); }
  CompileProgressLine(const CompileProgressLine&) = delete;
  CompileProgressLine& operator=(const CompileProgressLine&) = delete;

  void update(std::size_t done, std::size_t total);
  void finish() { line_.erase(); }

 private:
  std::string tool_;
  support::TerminalLine line_;
};

}  // namespace meldc
