// One simulated core's profile: node runs coalesced into spans of about a millisecond of
// simulated time (as the threaded runtime's recorder does with real time), idle and steal spans.
#pragma once

#include <cstdint>
#include <vector>

#include "simcore/time.hpp"
#include "support/profile_trace.hpp"

namespace multicore {

class CoreTimeline {
 public:
  void run(simcore::SimTime begin, simcore::SimTime end, std::uint64_t facts, std::size_t queued) {
    if (runs_ == 0) begin_ = begin;
    ++runs_;
    facts_ += facts;
    end_ = end;
    if (end_ - begin_ >= kSpanNanos) close(queued);
  }
  void factsIn(std::uint64_t n) { in_ += n; }
  void pause(support::ProfileSpan::Kind kind, simcore::SimTime begin, simcore::SimTime end,
             std::uint64_t nodesTaken = 0) {
    close(0);
    if (end > begin) spans_.push_back({kind, begin, end, nodesTaken, 0, 0, 0});
  }
  void finish() { close(0); }
  const std::vector<support::ProfileSpan>& spans() const { return spans_; }

 private:
  static constexpr simcore::SimTime kSpanNanos = 1'000'000;
  void close(std::size_t queued) {
    if (runs_ != 0) spans_.push_back({support::ProfileSpan::Kind::Run, begin_, end_, runs_, facts_, in_, queued});
    runs_ = facts_ = in_ = 0;
  }
  std::vector<support::ProfileSpan> spans_;
  simcore::SimTime begin_ = 0, end_ = 0;
  std::uint64_t runs_ = 0, facts_ = 0, in_ = 0;
};

}  // namespace multicore
