// How the multicore target balances work: when a rebalance may come and how many nodes a loaded
// worker hands an idle one. One policy for the threaded runtime (vm/threads/worker.cpp) and the
// simulated chip (targets/multicore/chip_simulator.cpp), so that the chip predicts what threads do.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace support {

struct StealPolicy {
  // A worker with this many nodes waiting has one to spare for an idle one.
  static constexpr std::size_t kStealableQueue = 2;
  // Rebalances come at least this far apart, and this many times their own cost apart, so that
  // they take a small share of the run even when the nodes that move carry many facts.
  static constexpr std::int64_t kRebalanceNanos = 500'000;
  static constexpr std::int64_t kRebalanceGap = 5;
  // How long after a rebalance that took `cost` ns the next one may start.
  static std::int64_t nextRebalanceAfter(double cost) {
    return std::max(kRebalanceNanos, std::int64_t(cost * double(kRebalanceGap) + 0.5));
  }

  // A worker's idle share of a window: its idle time there (its wait in the rebalance's first
  // barrier included: a worker that ran out and asked at once has been idle since) over the window.
  static double idleShare(double idle, double window) {
    return window > 0 ? std::clamp(idle / window, 0.0, 1.0) : 0.0;
  }

  // How many of its queued nodes `giver` hands to `taker`, from their queue lengths and the share
  // of the time since the last rebalance that each spent idle (0..1).
  //
  // Half the difference of the queues alone overshoots when queues say little about work: in a
  // program that runs in steps (pagerank), the worker that is behind has nearly every node
  // queued and the one ahead has few, so half the difference moved half the nodes, the next
  // rebalance moved them back, and the moves cost more than the idle time they saved. The
  // taker's idle share measures the imbalance itself: if the giver was busy a share b of the
  // time and the taker a share b - d, moving the work of d/2 of that time evens them out, which
  // is a share d / (2b) of the giver's queued work.
  static std::size_t nodesToGive(std::size_t giverQueue, std::size_t takerQueue, double giverIdle,
                                 double takerIdle) {
    if (giverQueue < takerQueue + kStealableQueue) return 0;
    const std::size_t byQueue = (giverQueue - takerQueue) / 2;
    const double giverBusy = std::max(1.0 - giverIdle, 1e-3);
    const double share = std::clamp((takerIdle - giverIdle) / (2 * giverBusy), 0.0, 0.5);
    const auto byIdle = std::size_t(std::ceil(double(giverQueue) * share - 1e-9));  // not 150.00000001 -> 151
    return std::max<std::size_t>(1, std::min(byQueue, byIdle));
  }
};

}  // namespace support
