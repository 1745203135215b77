// Run statistics and the run fingerprint.
#pragma once

#include <array>
#include <cstdint>
#include <ostream>

#include "simcore/event.hpp"

namespace simcore {

struct Statistics {
  std::array<std::uint64_t, std::size_t(EventKind::Count)> eventsByKind{};
  std::uint64_t eventsProcessed = 0;
  std::uint64_t messagesSent = 0;
  std::uint64_t messagesReceived = 0;
  std::uint64_t messagesDropped = 0;  // in flight when their link broke
  std::uint64_t bytesSent = 0;
  std::uint64_t motionsStarted = 0;
  std::uint64_t motionsEnded = 0;
  std::uint64_t timersCancelled = 0;
  std::uint64_t maxQueueSize = 0;
  SimTime simulatedTime = 0;
  double wallSeconds = 0;

  double eventsPerSecond() const { return wallSeconds > 0 ? double(eventsProcessed) / wallSeconds : 0; }
};

// A hash over every processed event (time, block, kind), in processing order: two runs with the same
// fingerprint processed the same events in the same order.
class Fingerprint {
 public:
  void add(SimTime time, std::uint32_t block, EventKind kind) {
    std::uint64_t x = std::uint64_t(time) * 0x9E3779B97F4A7C15ull ^
                      ((std::uint64_t(block) << 8) | std::uint64_t(kind)) * 0xC2B2AE3D27D4EB4Full;
    h_ = (((h_ << 27) | (h_ >> 37)) ^ x) * 0x100000001B3ull + 0x165667B19E3779F9ull;
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xCBF29CE484222325ull;
};

void printStatistics(std::ostream& out, const Statistics& stats, std::uint64_t fingerprint);

}  // namespace simcore
