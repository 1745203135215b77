// The progress line vsim shows on a terminal during long runs: simulated time, events, events/s.
// It appears only after a second of wall time (short runs stay clean) and is redrawn about four
// times a second in place, on stderr; finish() erases it so the summary starts on a clean line.
#pragma once

#include <chrono>
#include <optional>

#include "simcore/simulation.hpp"

namespace vsim {

class ProgressLine {
 public:
  ProgressLine(bool enabled, std::optional<simcore::SimTime> until);
  // Cheap enough to call after every slice of events: it looks at the clock and returns.
  void update(const simcore::Simulation& sim);
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  bool shown_ = false;
  std::optional<simcore::SimTime> until_;
  Clock::time_point start_, lastDraw_;
};

}  // namespace vsim
