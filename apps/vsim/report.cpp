#include "report.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <unordered_map>

#include "simcore/trace.hpp"

namespace vsim {

namespace {

// A printf into a std::string: the report is mostly fixed-width columns.
template <typename... Args>
std::string format(const char* fmt, Args... args) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

std::string rgbText(std::uint32_t rgb) { return format("#%06x", unsigned(rgb)); }

std::string rate(double eventsPerSecond, double wall) {
  if (wall <= 0) return "n/a (too short to time)";
  if (eventsPerSecond >= 1e6) return format("%.2f M", eventsPerSecond / 1e6);
  if (eventsPerSecond >= 1e3) return format("%.1f k", eventsPerSecond / 1e3);
  return format("%.0f", eventsPerSecond);
}

const char* endName(RunEnd end) {
  switch (end) {
    case RunEnd::QueueEmpty:
      return "queue-empty";
    case RunEnd::UntilReached:
      return "until";
    case RunEnd::Interrupted:
      return "interrupted";
  }
  return "?";
}

std::string endText(const simcore::Simulation& sim, const RunInfo& info) {
  const std::size_t n = sim.pendingEvents();
  const std::string pending = std::to_string(n) + (n == 1 ? " event pending" : " events pending");
  switch (info.end) {
    case RunEnd::QueueEmpty:
      return "queue empty";
    case RunEnd::UntilReached:
      return "--until reached, " + pending;
    case RunEnd::Interrupted:
      return "interrupted, " + pending;
  }
  return "?";
}

// The simulated time the run covered: with --until, a queue that empties early still means the
// world was simulated (quiet) up to that time.
simcore::SimTime simulatedTime(const simcore::Simulation& sim, const RunInfo& info) {
  if (info.until && info.end == RunEnd::QueueEmpty && *info.until > sim.now()) return *info.until;
  return sim.now();
}

void row(std::ostream& out, const char* name, const std::string& value) {
  out << format("  %-15s %s\n", name, value.c_str());
}

void jsonField(std::ostream& out, const char* key, std::string_view value, bool comma = true) {
  out << (comma ? "," : "") << '"' << key << "\":";
  simcore::writeJsonString(out, value);
}

}  // namespace

std::vector<ColorCount> colorHistogram(const simcore::World& world) {
  std::unordered_map<std::uint32_t, std::uint64_t> counts;
  for (simcore::BlockId id = 0; id < world.blockCount(); ++id)
    if (world.isAlive(id)) ++counts[world.block(id).color];
  std::vector<ColorCount> histogram;
  histogram.reserve(counts.size());
  for (const auto& [rgb, n] : counts) histogram.push_back({rgb, n});
  std::sort(histogram.begin(), histogram.end(), [](const ColorCount& a, const ColorCount& b) {
    return a.count != b.count ? a.count > b.count : a.rgb < b.rgb;
  });
  return histogram;
}

void printSummary(std::ostream& out, const simcore::Simulation& sim, const RunInfo& info) {
  const simcore::Statistics& s = sim.statistics();
  const simcore::World& world = sim.world();
  const std::size_t alive = world.aliveCount();

  row(out, "world", info.world);
  row(out, "block code", info.codeName + " (" + info.code + ")");
  row(out, "target", sim.target().name);
  row(out, "blocks", std::to_string(alive));
  row(out, "seed", std::to_string(sim.seed()));
  row(out, "end", endText(sim, info));
  row(out, "simulated time", simcore::formatTime(simulatedTime(sim, info)));
  row(out, "events", std::to_string(s.eventsProcessed));
  row(out, "wall time", format("%.3f s", s.wallSeconds));
  row(out, "events/s", rate(s.eventsPerSecond(), s.wallSeconds));
  row(out, "fingerprint", format("%016" PRIx64, sim.fingerprint()));
  for (const auto& [name, value] : info.counters) row(out, name.c_str(), std::to_string(value));

  // A long tail of colors says nothing more; the first ones and a count do.
  constexpr std::size_t kMaxColorsListed = 32;
  const std::vector<ColorCount> histogram = colorHistogram(world);
  row(out, "colors", std::to_string(histogram.size()) + " distinct");
  for (std::size_t i = 0; i < histogram.size() && i < kMaxColorsListed; ++i) {
    const char* name = simcore::colorName(histogram[i].rgb);
    out << format("    %s %-12s %8" PRIu64 "\n", rgbText(histogram[i].rgb).c_str(), name ? name : "",
                  histogram[i].count);
  }
  if (histogram.size() > kMaxColorsListed)
    out << "    ... " << histogram.size() - kMaxColorsListed << " more colors\n";

  if (alive > kMaxBlocksListed) return;
  const bool values = sim.target().hasDisplayValue;
  out << (values ? "  final blocks (id, cell, color, value)\n" : "  final blocks (id, cell, color)\n");
  for (simcore::BlockId id = 0; id < world.blockCount(); ++id) {
    const simcore::Block& b = world.block(id);
    if (!world.isAlive(id)) continue;
    const char* name = simcore::colorName(b.color);
    std::string line = format("    #%-3u %-12s %s %s", unsigned(id),
                              format("(%d,%d,%d)", b.cell.x, b.cell.y, b.cell.z).c_str(),
                              rgbText(b.color).c_str(), name ? name : "");
    if (values) line += format(" value=%d", sim.displayValue(id));
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << '\n';
  }
}

void writeJsonReport(std::ostream& out, const simcore::Simulation& sim, const RunInfo& info) {
  const simcore::Statistics& s = sim.statistics();
  const simcore::World& world = sim.world();
  const std::size_t alive = world.aliveCount();

  out << '{';
  jsonField(out, "world", info.world, false);
  jsonField(out, "code", info.code);
  jsonField(out, "code_name", info.codeName);
  jsonField(out, "target", sim.target().name);
  out << ",\"blocks\":" << alive << ",\"seed\":" << sim.seed();
  jsonField(out, "fes", sim.fesName());
  out << ",\"until_ns\":" << (info.until ? std::to_string(*info.until) : "null");
  jsonField(out, "end", endName(info.end));
  out << ",\"pending_events\":" << sim.pendingEvents() << ",\"simulated_ns\":" << simulatedTime(sim, info)
      << ",\"events\":" << s.eventsProcessed << format(",\"wall_s\":%.6f", s.wallSeconds)
      << format(",\"events_per_s\":%.0f", s.eventsPerSecond());
  jsonField(out, "fingerprint", format("%016" PRIx64, sim.fingerprint()));
  for (const auto& [name, value] : info.counters) {
    std::string key = name;
    for (char& c : key)
      if (c == ' ' || c == '/') c = '_';
    out << ",\"" << key << "\":" << value;
  }

  out << ",\"colors\":[";
  const std::vector<ColorCount> histogram = colorHistogram(world);
  for (std::size_t i = 0; i < histogram.size(); ++i) {
    const char* name = simcore::colorName(histogram[i].rgb);
    out << (i ? "," : "") << "{\"rgb\":\"" << rgbText(histogram[i].rgb) << "\",\"name\":";
    if (name)
      simcore::writeJsonString(out, name);
    else
      out << "null";
    out << ",\"count\":" << histogram[i].count << '}';
  }
  out << ']';

  if (alive <= kMaxBlocksListed) {
    out << ",\"final_blocks\":[";
    bool first = true;
    for (simcore::BlockId id = 0; id < world.blockCount(); ++id) {
      const simcore::Block& b = world.block(id);
      if (!world.isAlive(id)) continue;
      out << (first ? "" : ",")
          << format("{\"id\":%u,\"cell\":[%d,%d,%d],\"rgb\":\"%s\"", unsigned(id), b.cell.x, b.cell.y,
                    b.cell.z, rgbText(b.color).c_str());
      if (sim.target().hasDisplayValue) out << ",\"value\":" << sim.displayValue(id);
      out << '}';
      first = false;
    }
    out << ']';
  }

  out << ",\"statistics\":{\"events_by_kind\":{";
  bool first = true;
  for (std::size_t k = 0; k < s.eventsByKind.size(); ++k) {
    if (!s.eventsByKind[k]) continue;
    out << (first ? "" : ",") << '"' << simcore::eventKindName(simcore::EventKind(k))
        << "\":" << s.eventsByKind[k];
    first = false;
  }
  out << "},\"messages_sent\":" << s.messagesSent << ",\"messages_received\":" << s.messagesReceived
      << ",\"messages_dropped\":" << s.messagesDropped << ",\"bytes_sent\":" << s.bytesSent
      << ",\"motions_started\":" << s.motionsStarted << ",\"motions_ended\":" << s.motionsEnded
      << ",\"timers_cancelled\":" << s.timersCancelled << ",\"max_queue_size\":" << s.maxQueueSize << "}}\n";
}

}  // namespace vsim
