// A chip of N cores simulated on the discrete-event kernel (simcore's event queue): each core
// runs the nodes of its workload one at a time; a node run takes the core's time that its work
// costs (chip.hpp's CoreCosts); the facts it sends another core leave in batches (when the
// workload sends them, after a run) and cross the interconnect (hops × hop latency); a core
// that receives them pays to take them in.
// Idle cores steal as the threaded runtime does (vm/threads/worker.cpp): one core asks, every
// core finishes its current run and waits (a barrier), what is in transit is delivered, the i-th
// most loaded core gives to the i-th least loaded as many nodes as support::StealPolicy says (from
// their queues and idle time), and rounds are spaced as it says. set-cpu moves go through the
// same barrier.
// Deterministic: ties are broken by the kernel's (time, class, sequence) order.
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "chip.hpp"
#include "core_timeline.hpp"
#include "simcore/event_queue.hpp"
#include "support/profile_trace.hpp"

namespace multicore {

// What one node run (or a core's start) did; the chip turns it into time.
struct Work {
  std::uint64_t rules = 0, facts = 0;
  std::uint64_t tried = 0;  // facts the rules looked at, matching or not
};
// Facts one core sent another during a run; the workload keeps them under `handle`.
struct Batch {
  unsigned to = 0;
  std::uint64_t facts = 0, bytes = 0;
  std::uint64_t handle = 0;
};

// What runs on the chip (vsim's Meld shards; tests use small fakes).
class CoreWorkload {
 public:
  virtual ~CoreWorkload() = default;
  virtual Work start(unsigned core) = 0;
  // Runs the core's next node; false when it has none.
  virtual bool runNext(unsigned core, Work& work) = 0;
  virtual std::size_t queued(unsigned core) const = 0;
  // The batches `core` has for other cores, at most one per destination, when the workload's
  // batching sends them (after a node run; `force`: the core runs out of nodes, or stops for a
  // rebalance, and sends everything).
  virtual void takeOutgoing(unsigned core, std::vector<Batch>& out, bool force) = 0;
  virtual void deliver(unsigned core, std::uint64_t handle) = 0;
  // Work stealing: moves up to `count` of from's queued nodes to `to`; returns how many moved
  // and adds the bytes they carried (their facts) to `bytes`.
  virtual std::size_t moveNodes(unsigned from, unsigned to, std::size_t count, std::uint64_t& bytes) = 0;
  // set-cpu / set-affinity: whether moves wait, and doing them (inside the barrier); returns how
  // many nodes moved (and adds their bytes).
  virtual bool movesRequested() const = 0;
  virtual std::size_t applyRequestedMoves(std::uint64_t& bytes) = 0;
  virtual bool stopped() const = 0;  // stop-program
};

struct CoreStats {
  std::int64_t busyNs = 0, idleNs = 0, stealNs = 0;
  std::uint64_t nodeRuns = 0, rules = 0, facts = 0;
  std::uint64_t factsOut = 0, factsIn = 0, batchesOut = 0;
  std::uint64_t rebalances = 0, nodesTaken = 0, nodesGiven = 0;
};

class ChipSimulator {
 public:
  ChipSimulator(const ChipSpec& chip, CoreWorkload& workload, bool recordProfile = false);
  // Runs until no core has work and nothing is in transit, or stop-program.
  void run();
  simcore::SimTime endTime() const { return end_; }
  const std::vector<CoreStats>& cores() const { return stats_; }
  std::uint64_t rebalances() const { return rebalances_; }
  // A core's profile spans (with recordProfile).
  const std::vector<support::ProfileSpan>& spans(unsigned core) const { return timelines_.at(core).spans(); }
  // The run in the profile format of `meld --profile` (support/profile_trace.hpp), one lane per core.
  void writeProfile(std::ostream& out) const;

 private:
  struct InFlight {
    unsigned to;
    std::uint64_t facts, bytes, handle;
    simcore::SimTime arrival;
    bool delivered;
  };
  struct Core {
    bool scheduled = false;  // a run event is pending (the core is busy or about to be)
    bool inBarrier = false;
    simcore::SimTime idleSince = 0, barrierSince = 0;
    double owedNs = 0;  // receiving costs, paid in its next run
  };

  void runCore(unsigned core, simcore::SimTime now);
  void arrive(std::uint64_t slot, simcore::SimTime now);
  double send(unsigned core, simcore::SimTime now, double runNs, bool force);
  void wake(unsigned core, simcore::SimTime at);
  void goIdle(unsigned core, simcore::SimTime now);
  void requestRebalance(simcore::SimTime now, bool forced);
  void arriveAtBarrier(unsigned core, simcore::SimTime now);
  void completeBarrier(simcore::SimTime now);
  // Adds the bytes of the nodes moved to `bytes` and each taker's share to takenBytes[taker].
  std::size_t stealPlan(simcore::SimTime now, std::uint64_t& bytes, std::vector<std::uint64_t>& takenBytes);
  bool someoneCanGive(unsigned except) const;
  simcore::SimTime ns(double v) const { return simcore::SimTime(v + 0.5); }
  double workCost(const Work& w) const {
    return double(w.rules) * chip_.costs.rule + double(w.facts) * chip_.costs.fact +
           double(w.tried) * chip_.costs.tried;
  }
  double receiveCost(const InFlight& f) const {
    return double(f.facts) * chip_.costs.receive + double(f.bytes) * chip_.costs.byte;
  }

  ChipSpec chip_;
  CoreWorkload& work_;
  simcore::EventQueue queue_;
  std::vector<Core> core_;
  std::vector<CoreStats> stats_;
  std::vector<CoreTimeline> timelines_;  // empty unless profiling
  std::vector<InFlight> inFlight_;
  std::vector<std::uint64_t> freeSlots_;
  std::vector<Batch> outgoing_;
  unsigned idleCores_ = 0, inBarrier_ = 0;
  bool barrier_ = false;
  simcore::SimTime nextRebalance_ = 0, end_ = 0;
  simcore::SimTime windowStart_ = 0;        // the last rebalance's end: the idle shares are since then
  std::vector<std::int64_t> idleAtWindow_;  // per core
  std::uint64_t rebalances_ = 0;
};

}  // namespace multicore
