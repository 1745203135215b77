#include "simcore/trace.hpp"

#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <sstream>

#include "simcore/simulation.hpp"

namespace simcore {

// ---------------------------------------------------------------------------------------------
// Names
// ---------------------------------------------------------------------------------------------

namespace {

const char* traceKindName(int kind) {
  if (kind < int(EventKind::Count)) return eventKindName(EventKind(kind));
  switch (TraceKind(kind)) {
    case TraceKind::Send:
      return "send";
    case TraceKind::Drop:
      return "drop";
    case TraceKind::Color:
      return "color";
    case TraceKind::Motion:
      return "motion";
    case TraceKind::Text:
      return "trace";
    case TraceKind::Count:
      break;
  }
  return "?";
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

std::vector<std::string> traceKindNames() {
  std::vector<std::string> names;
  for (int k = 0; k < kTraceKindCount; ++k) names.emplace_back(traceKindName(k));
  return names;
}

std::optional<TraceFormat> parseTraceFormat(std::string_view name) {
  if (name == "text") return TraceFormat::Text;
  if (name == "json" || name == "jsonl") return TraceFormat::Json;
  return std::nullopt;
}

const char* colorName(std::uint32_t rgb) {
  struct Named {
    std::uint32_t rgb;
    const char* name;
  };
  // The palette of the example programs and the targets' default colors.
  static constexpr Named kColors[] = {
      {0x000000, "black"},  {0xFFFFFF, "white"},     {0xFF0000, "red"},        {0x00FF00, "green"},
      {0x0000FF, "blue"},   {0xFFFF00, "yellow"},    {0x00FFFF, "cyan"},       {0xFF00FF, "magenta"},
      {0xFFA500, "orange"}, {0x800080, "purple"},    {0xFFC0CB, "pink"},       {0x808080, "grey"},
      {0xC0C0C0, "silver"}, {0x404040, "dark-grey"}, {0x4080FF, "light-blue"}, {0x008000, "dark-green"},
      {0x000080, "navy"},   {0xA52A2A, "brown"},     {0xFFD700, "gold"},
  };
  for (const Named& c : kColors)
    if (c.rgb == rgb) return c.name;
  return nullptr;
}

void writeJsonString(std::ostream& out, std::string_view text) {
  out << '"';
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"':
        out << "\\\"";
        break;
      case '\\':
        out << "\\\\";
        break;
      case '\n':
        out << "\\n";
        break;
      case '\t':
        out << "\\t";
        break;
      case '\r':
        out << "\\r";
        break;
      default:
        if (c < 0x20) {
          char esc[8];
          std::snprintf(esc, sizeof esc, "\\u%04x", unsigned(c));
          out << esc;
        } else {
          out << ch;
        }
    }
  }
  out << '"';
}

// ---------------------------------------------------------------------------------------------
// Filter
// ---------------------------------------------------------------------------------------------

bool TraceFilter::selectsBlock(std::uint32_t id) const {
  if (blocks.empty()) return true;
  for (const auto& [lo, hi] : blocks)
    if (id >= lo && id <= hi) return true;
  return false;
}

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  for (;;) {
    const auto at = s.find(sep);
    parts.push_back(trim(s.substr(0, at)));
    if (at == std::string_view::npos) return parts;
    s.remove_prefix(at + 1);
  }
}

std::optional<std::uint32_t> parseId(std::string_view s) {
  std::uint32_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

class FilterParser {
 public:
  explicit FilterParser(std::string_view text) : text_(text) {}

  TraceFilter parse() {
    bool seen[4] = {};
    for (std::string_view clause : split(text_, ';')) {
      if (clause.empty() || clause == "all") continue;
      const auto eq = clause.find('=');
      if (eq == std::string_view::npos)
        fail("clause '" + std::string(clause) + "' is not key=value (keys: blocks, kinds, from, to)");
      const std::string_view key = trim(clause.substr(0, eq)), value = trim(clause.substr(eq + 1));
      const int index = key == "blocks" ? 0 : key == "kinds" ? 1 : key == "from" ? 2 : key == "to" ? 3 : -1;
      if (index < 0) fail("unknown key '" + std::string(key) + "' (keys: blocks, kinds, from, to)");
      if (seen[index]) fail("'" + std::string(key) + "' is given twice");
      seen[index] = true;
      if (value.empty()) fail("'" + std::string(key) + "' has no value");
      if (index == 0) parseBlocks(value);
      if (index == 1) parseKinds(value);
      if (index == 2) filter_.from = parseTime(key, value);
      if (index == 3) filter_.to = parseTime(key, value);
    }
    if (filter_.from > filter_.to) fail("'from' is after 'to'");
    return filter_;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw TraceFilterError("bad trace filter '" + std::string(text_) + "': " + why);
  }

  void parseBlocks(std::string_view value) {
    for (std::string_view item : split(value, ',')) {
      const auto dash = item.find('-');
      const auto lo = parseId(trim(item.substr(0, dash)));
      const auto hi = dash == std::string_view::npos ? lo : parseId(trim(item.substr(dash + 1)));
      if (!lo || !hi) fail("blocks: '" + std::string(item) + "' is not a block id or a range like 5-9");
      if (*lo > *hi) fail("blocks: range '" + std::string(item) + "' is empty (from > to)");
      filter_.blocks.emplace_back(*lo, *hi);
    }
  }

  void parseKinds(std::string_view value) {
    std::uint32_t mask = 0;
    const std::vector<std::string> names = traceKindNames();
    for (std::string_view item : split(value, ',')) {
      if (item == "all") {
        mask = (1u << kTraceKindCount) - 1;
        continue;
      }
      if (item == "events") {
        mask |= (1u << unsigned(EventKind::Count)) - 1;
        continue;
      }
      if (item == "neighbor") {
        mask |= (1u << unsigned(EventKind::NeighborAdded)) | (1u << unsigned(EventKind::NeighborRemoved));
        continue;
      }
      int found = -1;
      for (int k = 0; k < kTraceKindCount; ++k)
        if (item == names[std::size_t(k)]) found = k;
      if (found < 0)
        fail("unknown kind '" + std::string(item) + "' (kinds: " + joined(names) +
             "; groups: all, events, neighbor)");
      mask |= 1u << unsigned(found);
    }
    filter_.kinds = mask;
  }

  SimTime parseTime(std::string_view key, std::string_view value) const {
    const auto t = parseDuration(value);
    if (!t)
      fail(std::string(key) + ": '" + std::string(value) + "' is not a duration like 1.5s, 250ms or 10us");
    return *t;
  }

  std::string_view text_;
  TraceFilter filter_;
};

}  // namespace

TraceFilter parseTraceFilter(std::string_view text) { return FilterParser(text).parse(); }

// ---------------------------------------------------------------------------------------------
// Output
// ---------------------------------------------------------------------------------------------

// One output line: built field by field into a buffer, written whole by the destructor so that a
// line is never split by other output on the same stream.
class Trace::Line {
 public:
  Line(Trace& trace, const Simulation& sim, std::uint32_t block, int kind)
      : trace_(trace), sim_(sim), json_(trace.format_ == TraceFormat::Json) {
    char head[96];
    const SimTime t = sim.now();
    if (json_)
      std::snprintf(head, sizeof head, "{\"t_ns\":%" PRId64 ",\"block\":%" PRIu32 ",\"kind\":\"%s\"", t,
                    block, traceKindName(kind));
    else
      std::snprintf(head, sizeof head, "%16s  #%-6" PRIu32 " %-15s", formatTime(t).c_str(), block,
                    traceKindName(kind));
    buf_ = head;
  }
  ~Line() {
    if (!json_)  // the kind column is padded; a record without fields must not end in blanks
      while (!buf_.empty() && buf_.back() == ' ') buf_.pop_back();
    buf_ += json_ ? "}\n" : "\n";
    trace_.out_.write(buf_.data(), std::streamsize(buf_.size()));
    ++trace_.lines_;
  }

  Line& num(const char* key, std::int64_t v) { return raw(key, std::to_string(v)); }
  Line& block(const char* key, std::uint32_t id) {
    // Appended rather than "#" + to_string(...): GCC 12 gives a false -Wrestrict on the latter.
    std::string value = json_ ? "" : "#";
    value += std::to_string(id);
    return raw(key, value);
  }
  Line& face(const char* key, int f) {
    const auto& names = sim_.target().faceNames;
    if (f < 0 || std::size_t(f) >= names.size()) return num(key, f);
    return raw(key, json_ ? "\"" + names[std::size_t(f)] + "\"" : names[std::size_t(f)]);
  }
  Line& time(const char* key, SimTime t) { return raw(key, json_ ? std::to_string(t) : formatTime(t)); }
  Line& cell(const char* key, const Cell& c) {
    char s[64];
    std::snprintf(s, sizeof s, json_ ? "[%d,%d,%d]" : "(%d,%d,%d)", c.x, c.y, c.z);
    return raw(key, s);
  }
  Line& color(std::uint32_t rgb) {
    char s[16];
    std::snprintf(s, sizeof s, json_ ? "\"#%06x\"" : "#%06x", unsigned(rgb));
    raw("rgb", s);
    const char* name = colorName(rgb);
    return name ? raw("name", json_ ? std::string("\"") + name + "\"" : name) : *this;
  }
  Line& text(std::string_view t) {
    if (json_) {
      std::ostringstream s;
      writeJsonString(s, t);
      return raw("text", s.str());
    }
    // Keep one record per line: a program's newlines are shown escaped.
    buf_ += ' ';
    for (const char ch : t) {
      if (ch == '\n')
        buf_ += "\\n";
      else
        buf_ += ch;
    }
    return *this;
  }

 private:
  Line& raw(const char* key, const std::string& value) {
    if (json_) {
      buf_ += ",\"";
      buf_ += key;
      buf_ += "\":";
    } else {
      buf_ += ' ';
      buf_ += key;
      buf_ += '=';
    }
    buf_ += value;
    return *this;
  }

  Trace& trace_;
  const Simulation& sim_;
  bool json_;
  std::string buf_;
};

Trace::Trace(std::ostream& out, TraceFilter filter, TraceFormat format)
    : out_(out), filter_(std::move(filter)), format_(format) {}

bool Trace::selected(const Simulation& sim, int kind, std::uint32_t block, std::uint32_t other) const {
  if (!filter_.selectsKind(kind) || !filter_.selectsTime(sim.now())) return false;
  return filter_.selectsBlock(block) || (other != 0xFFFFFFFFu && filter_.selectsBlock(other));
}

void Trace::onEvent(const Simulation& sim, const Event& e) {
  if (!selected(sim, int(e.kind), e.block)) return;
  Line line(*this, sim, e.block, int(e.kind));
  switch (e.kind) {
    case EventKind::Message:
      // Called before delivery with the link intact: the sender is the neighbor on that face.
      line.face("face", e.face).block("from", sim.world().neighbor(e.block, e.face));
      break;
    case EventKind::NeighborAdded:
    case EventKind::NeighborRemoved:
      line.face("face", e.face).block("neighbor", std::uint32_t(e.arg));
      break;
    case EventKind::MotionEnd:
      line.cell("cell", sim.world().block(e.block).cell);
      break;
    default:  // a timer's event argument is kernel-internal (slot or tag): nothing to show
      break;
  }
}

void Trace::onMessageSent(const Simulation& sim, std::uint32_t from, int face, std::uint32_t to,
                          std::uint32_t size, SimTime arrival) {
  if (!selected(sim, int(TraceKind::Send), from, to)) return;
  Line(*this, sim, from, int(TraceKind::Send))
      .face("face", face)
      .block("to", to)
      .num("size", size)
      .time("arrival", arrival);
}

void Trace::onMessageDropped(const Simulation& sim, std::uint32_t from, int face, std::uint32_t to) {
  if (!selected(sim, int(TraceKind::Drop), from, to)) return;
  Line(*this, sim, from, int(TraceKind::Drop)).face("face", face).block("to", to);
}

void Trace::onColorChanged(const Simulation& sim, std::uint32_t block, std::uint32_t rgb) {
  if (!selected(sim, int(TraceKind::Color), block)) return;
  Line(*this, sim, block, int(TraceKind::Color)).color(rgb);
}

void Trace::onMotionStarted(const Simulation& sim, std::uint32_t block, const Cell& from, const Cell& to,
                            SimTime end) {
  if (!selected(sim, int(TraceKind::Motion), block)) return;
  Line(*this, sim, block, int(TraceKind::Motion)).cell("from", from).cell("to", to).time("end", end);
}

void Trace::onBlockTrace(const Simulation& sim, std::uint32_t block, std::string_view text) {
  if (!selected(sim, int(TraceKind::Text), block)) return;
  Line(*this, sim, block, int(TraceKind::Text)).text(text);
}

}  // namespace simcore
