// The progress line vsim shows on a terminal during long runs: simulated time, events, events/s
// (support::TerminalLine: after a second, about four times a second, in place on stderr); finish()
// erases it so the summary starts on a clean line.
#pragma once

#include <optional>

#include "simcore/simulation.hpp"
#include "support/terminal_line.hpp"

namespace vsim {

class ProgressLine {
 public:
  ProgressLine(bool enabled, std::optional<simcore::SimTime> until) : line_(enabled), until_(until) {}
  // Cheap enough to call after every slice of events: it looks at the clock and returns.
  void update(const simcore::Simulation& sim);
  void finish() { line_.erase(); }

 private:
  support::TerminalLine line_;
  std::optional<simcore::SimTime> until_;
};

}  // namespace vsim
