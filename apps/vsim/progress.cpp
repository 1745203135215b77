#include "progress.hpp"

#include <cinttypes>
#include <cstdio>

namespace vsim {

void ProgressLine::update(const simcore::Simulation& sim) {
  if (!line_.due()) return;
  const double wall = line_.elapsedSeconds();
  const std::uint64_t events = sim.statistics().eventsProcessed;
  char percent[32] = "";
  if (until_ && *until_ > 0)
    std::snprintf(percent, sizeof percent, " (%3.0f%%)", 100.0 * double(sim.now()) / double(*until_));
  char text[192];
  std::snprintf(text, sizeof text,
                "  simulated %.3f s%s   %" PRIu64 " events   %.2f M events/s   wall %.1f s",
                double(sim.now()) / 1e9, percent, events, double(events) / wall / 1e6, wall);
  line_.draw(text);
}

}  // namespace vsim
