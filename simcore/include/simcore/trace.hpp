// Tracing a run: an observer that writes one line per selected happening — kernel events, messages
// sent and dropped, color changes, motions, and the block program's own trace text — as readable
// text or as JSON lines, filtered by block ids, kinds and a time window.
//
// Filter syntax (command line: `vsim --trace FILTER`): clauses separated by ';', each `key=value`:
//   blocks=0,5-9         block ids and inclusive ranges (default: all blocks)
//   kinds=message,tap    record kinds (default: all); see traceKindNames()
//   from=1s  to=2.5s     inclusive time window, durations as in parseDuration (default: whole run)
// An empty filter or "all" selects everything. Sends and drops match when either end is selected.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "simcore/event.hpp"
#include "simcore/observer.hpp"
#include "simcore/time.hpp"

namespace simcore {

// Record kinds: the kernel's event kinds first (same numbering as EventKind), then what the
// observer interface reports besides events.
enum class TraceKind : std::uint8_t {
  Send = std::uint8_t(EventKind::Count),  // a message was queued on a link ("send")
  Drop,                                   // a message in flight was lost ("drop")
  Color,                                  // a block changed color ("color")
  Motion,                                 // a motion started ("motion")
  Text,                                   // the block program's trace service ("trace")
  Count
};
inline constexpr int kTraceKindCount = int(TraceKind::Count);

// Every accepted name, in record-kind order: eventKindName(...) for events, then send, drop,
// color, motion, trace.
std::vector<std::string> traceKindNames();

class TraceFilterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TraceFilter {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> blocks;  // inclusive ranges; empty = all
  std::uint32_t kinds = (1u << kTraceKindCount) - 1;            // bit per record kind
  SimTime from = 0;
  SimTime to = kTimeInfinity;

  bool selectsBlock(std::uint32_t id) const;
  bool selectsKind(int kind) const { return (kinds >> kind) & 1u; }
  bool selectsTime(SimTime t) const { return t >= from && t <= to; }
};

// Parses the syntax above; throws TraceFilterError saying what is wrong and what is expected.
TraceFilter parseTraceFilter(std::string_view text);

enum class TraceFormat { Text, Json };
std::optional<TraceFormat> parseTraceFormat(std::string_view name);

// "red", "orange", ... for the colors block programs commonly use (exact 0xRRGGBB), else nullptr.
const char* colorName(std::uint32_t rgb);

// Writes `text` as a JSON string literal (quotes included), escaping what JSON requires.
void writeJsonString(std::ostream& out, std::string_view text);

class Trace final : public SimulationObserver {
 public:
  Trace(std::ostream& out, TraceFilter filter, TraceFormat format);

  void onEvent(const Simulation& sim, const Event& e) override;
  void onMessageSent(const Simulation& sim, std::uint32_t from, int face, std::uint32_t to,
                     std::uint32_t size, SimTime arrival) override;
  void onMessageDropped(const Simulation& sim, std::uint32_t from, int face, std::uint32_t to) override;
  void onColorChanged(const Simulation& sim, std::uint32_t block, std::uint32_t rgb) override;
  void onMotionStarted(const Simulation& sim, std::uint32_t block, const Cell& from, const Cell& to,
                       SimTime end) override;
  void onBlockTrace(const Simulation& sim, std::uint32_t block, std::string_view text) override;

  std::uint64_t linesWritten() const { return lines_; }
  // Only the kinds the filter selects: kernel events, sends.
  bool wantsEvents() const override {
    for (int k = 0; k < int(EventKind::Count); ++k)
      if (filter_.selectsKind(k)) return true;
    return false;
  }
  bool wantsMessages() const override { return filter_.selectsKind(int(TraceKind::Send)); }

 private:
  class Line;
  bool selected(const Simulation& sim, int kind, std::uint32_t block,
                std::uint32_t other = 0xFFFFFFFFu) const;

  std::ostream& out_;
  TraceFilter filter_;
  TraceFormat format_;
  std::uint64_t lines_ = 0;
};

}  // namespace simcore
