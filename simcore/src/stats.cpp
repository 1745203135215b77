#include "simcore/stats.hpp"

#include <cinttypes>
#include <cstdio>

namespace simcore {

void printStatistics(std::ostream& out, const Statistics& s, std::uint64_t fingerprint) {
  char line[160];
  auto row = [&](const char* name, std::uint64_t v) {
    std::snprintf(line, sizeof line, "  %-22s %" PRIu64 "\n", name, v);
    out << line;
  };
  out << "statistics:\n";
  row("events processed", s.eventsProcessed);
  for (std::size_t k = 0; k < s.eventsByKind.size(); ++k)
    if (s.eventsByKind[k]) {
      std::snprintf(line, sizeof line, "    %-20s %" PRIu64 "\n", eventKindName(EventKind(k)),
                    s.eventsByKind[k]);
      out << line;
    }
  row("messages sent", s.messagesSent);
  row("messages received", s.messagesReceived);
  row("messages dropped", s.messagesDropped);
  row("bytes sent", s.bytesSent);
  row("motions started", s.motionsStarted);
  row("motions ended", s.motionsEnded);
  row("timers cancelled", s.timersCancelled);
  row("max queue size", s.maxQueueSize);
  std::snprintf(line, sizeof line, "  %-22s %.9f s\n", "simulated time", double(s.simulatedTime) / 1e9);
  out << line;
  std::snprintf(line, sizeof line, "  %-22s %.3f s\n", "wall time", s.wallSeconds);
  out << line;
  std::snprintf(line, sizeof line, "  %-22s %.0f\n", "events/s", s.eventsPerSecond());
  out << line;
  std::snprintf(line, sizeof line, "  %-22s %016" PRIx64 "\n", "fingerprint", fingerprint);
  out << line;
}

}  // namespace simcore
