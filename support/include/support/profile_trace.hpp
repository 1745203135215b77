// The profile format of the multicore target, written by `meld --profile` (real threads) and by
// `vsim --target multicore --profile` (a simulated chip), read by the IDE's profile view: Chrome's
// trace-event JSON, which Perfetto and chrome://tracing open. One lane (tid) per worker thread or
// core, holding spans: node runs coalesced into spans of about a millisecond (counts of node runs,
// facts derived, facts from other lanes), idle spans and steal spans (nodes taken); two counters
// per run span (facts derived per ms over it, queued nodes at its end). One writer, so that the
// threaded runtime and the simulator cannot drift apart.
#pragma once

#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace support {

struct ProfileSpan {
  enum class Kind : std::uint8_t { Run, Idle, Steal };
  Kind kind;
  std::int64_t beginNs, endNs;  // since the run's start
  // Run: during the span, and the queue at its end; Steal: nodeRuns holds the nodes taken.
  std::uint64_t nodeRuns, factsDerived, factsIn, waiting;
};

struct ProfileLane {
  std::string name;  // "worker 0", "core 3"
  const std::vector<ProfileSpan>* spans;
};

namespace detail {

inline void writeProfileSpan(std::ostream& out, unsigned tid, const ProfileSpan& s) {
  char line[512];
  const double ts = double(s.beginNs) / 1000.0, dur = double(s.endNs - s.beginNs) / 1000.0;
  if (s.kind == ProfileSpan::Kind::Idle) {
    std::snprintf(
        line, sizeof line,
        ",\n{\"name\":\"idle\",\"cat\":\"idle\",\"ph\":\"X\",\"pid\":1,\"tid\":%u,\"ts\":%.3f,\"dur\":%.3f}",
        tid, ts, dur);
    out << line;
    return;
  }
  if (s.kind == ProfileSpan::Kind::Steal) {
    std::snprintf(line, sizeof line,
                  ",\n{\"name\":\"steal\",\"cat\":\"steal\",\"ph\":\"X\",\"pid\":1,\"tid\":%u,\"ts\":%.3f,"
                  "\"dur\":%.3f,\"args\":{\"nodes taken\":%llu}}",
                  tid, ts, dur, (unsigned long long)s.nodeRuns);
    out << line;
    return;
  }
  std::snprintf(
      line, sizeof line,
      ",\n{\"name\":\"node runs\",\"cat\":\"run\",\"ph\":\"X\",\"pid\":1,\"tid\":%u,\"ts\":%.3f,"
      "\"dur\":%.3f,\"args\":{\"node runs\":%llu,\"facts derived\":%llu,\"facts from other threads\":%llu}}",
      tid, ts, dur, (unsigned long long)s.nodeRuns, (unsigned long long)s.factsDerived,
      (unsigned long long)s.factsIn);
  out << line;
  const double perMs = dur > 0 ? double(s.factsDerived) * 1000.0 / dur : 0.0;
  std::snprintf(line, sizeof line,
                ",\n{\"name\":\"facts derived per ms, thread %u\",\"ph\":\"C\",\"pid\":1,\"ts\":%.3f,"
                "\"args\":{\"facts\":%.1f}}"
                ",\n{\"name\":\"queued nodes, thread "
                "%u\",\"ph\":\"C\",\"pid\":1,\"ts\":%.3f,\"args\":{\"nodes\":%llu}}",
                tid, ts, perMs, tid, double(s.endNs) / 1000.0, (unsigned long long)s.waiting);
  out << line;
}

inline std::string jsonEscaped(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '"' || c == '\\') r += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) r += c;
  }
  return r;
}

}  // namespace detail

// `process` names the run: "meld -j N" for threads, "vsim multicore N cores" for a chip (the
// IDE's profile view accepts these two).
inline void writeProfileTrace(std::ostream& out, const std::string& process,
                              const std::vector<ProfileLane>& lanes) {
  out << "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n"
         "{\"name\":\"process_name\",\"ph\":\"M\",\"pid\":1,\"args\":{\"name\":\""
      << detail::jsonEscaped(process) << "\"}}";
  for (unsigned t = 0; t < lanes.size(); ++t) {
    out << ",\n{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":" << t << ",\"args\":{\"name\":\""
        << detail::jsonEscaped(lanes[t].name) << "\"}}";
    if (lanes[t].spans)
      for (const ProfileSpan& s : *lanes[t].spans) detail::writeProfileSpan(out, t, s);
  }
  out << "\n]}\n";
}

}  // namespace support
