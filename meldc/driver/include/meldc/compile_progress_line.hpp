// The progress line meldc, meld and vsim show on a terminal while native code compiles (a large
// program takes seconds to minutes): parts compiled out of all, and the wall time. It appears only
// after a second (small programs stay quiet), is redrawn at most four times a second in place on
// stderr, and finish() erases it.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace meldc {

class CompileProgressLine {
 public:
  // `enabled`: draw at all (the callers pass whether stderr is a terminal, and their --no-progress).
  CompileProgressLine(std::string tool, bool enabled);
  ~CompileProgressLine() { finish(); }
  CompileProgressLine(const CompileProgressLine&) = delete;
  CompileProgressLine& operator=(const CompileProgressLine&) = delete;

  void update(std::size_t done, std::size_t total);
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  std::string tool_;
  bool enabled_, shown_ = false;
  Clock::time_point start_, lastDraw_;
};

}  // namespace meldc
