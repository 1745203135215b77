// One simulated core's profile, in windows of about a millisecond of simulated time (as the
// threaded runtime's recorder coalesces node runs over real time): a window holds many node runs
// and the short idle gaps between them (a core that waits a few microseconds for facts from
// another core is the common case on a chip), written as one run span of the window's busy time
// followed by one idle span of its idle time. So the busy and idle totals are exact and a file
// holds at most two spans per core and millisecond. An idle gap of a millisecond or more, and a
// steal (rebalance), are spans of their own.
#pragma once

#include <cstdint>
#include <vector>

#include "simcore/time.hpp"
#include "support/profile_trace.hpp"

namespace multicore {

class CoreTimeline {
 public:
  // runs: 1 for a node run, 0 for a core's start (its axioms).
  void run(simcore::SimTime begin, simcore::SimTime end, std::uint64_t facts, std::size_t queued,
           std::uint64_t runs = 1) {
    open(begin);
    busy_ += end - begin;
    runs_ += runs;
    facts_ += facts;
    queued_ = queued;
    if (end - windowBegin_ >= kWindowNanos) flush();
  }
  void factsIn(std::uint64_t n) { in_ += n; }
  void idle(simcore::SimTime begin, simcore::SimTime end) {
    if (end <= begin) return;
    if (end - begin >= kWindowNanos) {
      flush();
      spans_.push_back({support::ProfileSpan::Kind::Idle, begin, end, 0, 0, 0, 0});
      return;
    }
    open(begin);
    idle_ += end - begin;
    if (end - windowBegin_ >= kWindowNanos) flush();
  }
  void steal(simcore::SimTime begin, simcore::SimTime end, std::uint64_t nodesTaken) {
    flush();
    if (end > begin) spans_.push_back({support::ProfileSpan::Kind::Steal, begin, end, nodesTaken, 0, 0, 0});
  }
  void finish() { flush(); }
  const std::vector<support::ProfileSpan>& spans() const { return spans_; }

 private:
  static constexpr simcore::SimTime kWindowNanos = 1'000'000;
  void open(simcore::SimTime at) {
    if (!windowOpen_) windowBegin_ = at, windowOpen_ = true;
  }
  void flush() {
    if (!windowOpen_) return;
    const simcore::SimTime busyEnd = windowBegin_ + busy_;
    if (busy_ != 0 || runs_ != 0)
      spans_.push_back({support::ProfileSpan::Kind::Run, windowBegin_, busyEnd, runs_, facts_, in_, queued_});
    if (idle_ != 0)
      spans_.push_back({support::ProfileSpan::Kind::Idle, busyEnd, busyEnd + idle_, 0, 0, 0, 0});
    windowOpen_ = false;
    busy_ = idle_ = 0;
    runs_ = facts_ = in_ = 0;
  }
  std::vector<support::ProfileSpan> spans_;
  bool windowOpen_ = false;
  simcore::SimTime windowBegin_ = 0, busy_ = 0, idle_ = 0;
  std::uint64_t runs_ = 0, facts_ = 0, in_ = 0, queued_ = 0;
};

}  // namespace multicore
