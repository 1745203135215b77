// What one worker thread did over time, for `meld --profile FILE.json` (Chrome's trace-event
// format, which Perfetto and chrome://tracing open). Node runs are coalesced into spans: a span
// ends when the thread runs out of work or after kSpanNanos, so a file holds a few thousand
// events per thread-second rather than one per node run. The clock is read once per kClockEvery
// node runs, which keeps the cost of a profiled run low. Off (no recorder), a worker pays one
// test per node run.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "support/profile_trace.hpp"

namespace meldvm::threads {

class ProfileRecorder {
 public:
  using Kind = support::ProfileSpan::Kind;
  using Span = support::ProfileSpan;

  explicit ProfileRecorder(std::chrono::steady_clock::time_point origin) : origin_(origin) {
    spans_.reserve(4096);
  }

  // A node run ended (derived: the thread's facts derived so far; waiting: its queue length).
  void nodeRun(std::uint64_t derived, std::uint64_t factsIn, std::size_t waiting) {
    ++runs_;
    if (++sinceClock_ < kClockEvery) return;
    sinceClock_ = 0;
    const std::int64_t now = nanos();
    if (now - spanBegin_ >= kSpanNanos) closeRun(now, derived, factsIn, waiting);
  }
  // The thread ran out of work (Idle) or joined a rebalance (Steal): the running span ends, a
  // pause begins; pauseEnd records it (nodes: taken by the thread during a Steal).
  void pauseBegin(std::uint64_t derived, std::uint64_t factsIn) {
    closeRun(nanos(), derived, factsIn, 0);
    pauseBegin_ = spanBegin_;
  }
  void pauseEnd(Kind kind, std::uint64_t nodes = 0) {
    const std::int64_t now = nanos();
    spans_.push_back({kind, pauseBegin_, now, nodes, 0, 0, 0});
    spanBegin_ = now;
  }
  void finish(std::uint64_t derived, std::uint64_t factsIn) { closeRun(nanos(), derived, factsIn, 0); }
  const std::vector<Span>& spans() const { return spans_; }

 private:
  static constexpr std::int64_t kSpanNanos = 1'000'000;
  static constexpr unsigned kClockEvery = 8;

  std::int64_t nanos() const {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - origin_)
        .count();
  }
  // With no node run ended since the last span, nothing is recorded and the facts counted so far
  // stay for the next span: a rebalance joined from a safe point comes in the middle of a run.
  void closeRun(std::int64_t now, std::uint64_t derived, std::uint64_t factsIn, std::size_t waiting) {
    if (runs_ != 0) {
      spans_.push_back(
          {Kind::Run, spanBegin_, now, runs_, derived - derivedAt_, factsIn - factsInAt_, waiting});
      derivedAt_ = derived;
      factsInAt_ = factsIn;
    }
    runs_ = 0;
    sinceClock_ = 0;
    spanBegin_ = now;
  }

  std::chrono::steady_clock::time_point origin_;
  std::vector<Span> spans_;
  std::int64_t spanBegin_ = 0, pauseBegin_ = 0;
  std::uint64_t runs_ = 0, derivedAt_ = 0, factsInAt_ = 0;
  unsigned sinceClock_ = 0;
};

}  // namespace meldvm::threads
