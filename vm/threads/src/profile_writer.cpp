// ThreadedMachine::writeProfile: the recorders' spans as Chrome trace events ("X" complete events
// in microseconds, "C" counters, "M" thread names), one tid per worker thread.
#include <cstdio>
#include <ostream>

#include "meldvm/threaded_machine.hpp"
#include "worker.hpp"

namespace meldvm {

namespace {

void writeSpan(std::ostream& out, unsigned tid, const threads::ProfileRecorder::Span& s) {
  char line[512];
  const double ts = double(s.beginNs) / 1000.0, dur = double(s.endNs - s.beginNs) / 1000.0;
  if (s.kind == threads::ProfileRecorder::Kind::Idle) {
    std::snprintf(
        line, sizeof line,
        ",\n{\"name\":\"idle\",\"cat\":\"idle\",\"ph\":\"X\",\"pid\":1,\"tid\":%u,\"ts\":%.3f,\"dur\":%.3f}",
        tid, ts, dur);
    out << line;
    return;
  }
  if (s.kind == threads::ProfileRecorder::Kind::Steal) {
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
  // Counters: facts derived per millisecond over the span, and the queue at its end.
  const double perMs = dur > 0 ? double(s.factsDerived) * 1000.0 / dur : 0.0;
  std::snprintf(line, sizeof line,
                ",\n{\"name\":\"facts derived per ms, thread %u\",\"ph\":\"C\",\"pid\":1,\"ts\":%.3f,"
                "\"args\":{\"facts\":%.1f}}"
                ",\n{\"name\":\"queued nodes, thread "
                "%u\",\"ph\":\"C\",\"pid\":1,\"ts\":%.3f,\"args\":{\"nodes\":%llu}}",
                tid, ts, perMs, tid, double(s.endNs) / 1000.0, (unsigned long long)s.waiting);
  out << line;
}

}  // namespace

void ThreadedMachine::writeProfile(std::ostream& out) const {
  out << "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n"
         "{\"name\":\"process_name\",\"ph\":\"M\",\"pid\":1,\"args\":{\"name\":\"meld -j "
      << workers_.size() << "\"}}";
  for (unsigned t = 0; t < workers_.size(); ++t) {
    out << ",\n{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":" << t
        << ",\"args\":{\"name\":\"worker " << t << "\"}}";
    if (const threads::ProfileRecorder* r = workers_[t]->profile())
      for (const auto& s : r->spans()) writeSpan(out, t, s);
  }
  out << "\n]}\n";
}

}  // namespace meldvm
