// A profile of the multicore target as `meld --profile FILE.json` (worker threads) or
// `vsim --target multicore --profile FILE.json` (the cores of a simulated chip) writes it (Chrome
// trace events, support/profile_trace.hpp): per thread or core, spans of node runs, idle spans
// and steal spans. Read back here for the IDE's profile view; several profiles of the same
// program at different thread counts make a speedup table.
#pragma once

#include <QString>
#include <optional>
#include <vector>

namespace ide {

struct ProfileSpan {
  enum class Kind { Run, Idle, Steal };
  Kind kind;
  double beginUs, endUs;
  unsigned long long nodeRuns = 0, facts = 0;  // a Run span: node runs, facts derived; Steal: nodes taken
};

struct ThreadSummary {
  double runUs = 0, idleUs = 0, stealUs = 0;
  unsigned long long nodeRuns = 0, facts = 0, nodesTaken = 0;
};

struct Profile {
  QString path, title;                            // title: "meld -j 2", "vsim multicore 16 cores"
  std::vector<std::vector<ProfileSpan>> threads;  // per worker thread (or core), in time order
  std::vector<QString> laneNames;                 // per thread: "worker 0", "core 0"
  bool simulated = false;                         // a simulated chip: its times are predicted
  double endUs = 0;                               // the last span's end: the run's wall time
  std::vector<ThreadSummary> summary;             // per thread
};

// Reads a profile; on failure nullopt and `error` says why (file, JSON, or not a meld profile).
std::optional<Profile> loadProfile(const QString& path, QString& error);

// One row of a -j sweep: the profiles ordered by thread count, speedup against the fewest threads.
struct SweepRow {
  int threads;
  double wallSeconds, speedup, efficiency;
};
std::vector<SweepRow> sweep(const std::vector<Profile>& profiles);

}  // namespace ide
