#include "progress.hpp"

#include <cinttypes>
#include <cstdio>

namespace vsim {

ProgressLine::ProgressLine(bool enabled, std::optional<simcore::SimTime> until)
    : enabled_(enabled), until_(until), start_(Clock::now()), lastDraw_(start_) {}

void ProgressLine::update(const simcore::Simulation& sim) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (now - start_ < std::chrono::seconds(1) || now - lastDraw_ < std::chrono::milliseconds(250)) return;
  lastDraw_ = now;
  shown_ = true;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const std::uint64_t events = sim.statistics().eventsProcessed;
  char percent[32] = "";
  if (until_ && *until_ > 0)
    std::snprintf(percent, sizeof percent, " (%3.0f%%)", 100.0 * double(sim.now()) / double(*until_));
  // \r and "erase to end of line": the line is redrawn in place whatever its previous length.
  std::fprintf(stderr, "\r\033[K  simulated %.3f s%s   %" PRIu64 " events   %.2f M events/s   wall %.1f s",
               double(sim.now()) / 1e9, percent, events, double(events) / wall / 1e6, wall);
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace vsim
