#include "chip_simulator.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "simcore/future_event_set.hpp"
#include "support/steal_policy.hpp"

namespace multicore {

namespace {

// A core's next node run is a Timer event of the core; a batch arriving at a core is a Message
// event (arg: its in-flight slot). Messages come first at equal times, as in the kernel.
constexpr simcore::EventKind kRun = simcore::EventKind::Timer;
constexpr simcore::EventKind kArrival = simcore::EventKind::Message;
using support::StealPolicy;
constexpr std::size_t kStealableQueue = StealPolicy::kStealableQueue;

}  // namespace

ChipSimulator::ChipSimulator(const ChipSpec& chip, CoreWorkload& workload, bool recordProfile)
    : chip_(chip),
      work_(workload),
      queue_(simcore::makeFutureEventSet(simcore::FesKind::Heap)),
      core_(chip.cores),
      stats_(chip.cores),
      idleAtWindow_(chip.cores) {
  if (chip.cores == 0) throw std::invalid_argument("a chip needs at least one core");
  if (recordProfile) timelines_.resize(chip.cores);
}

void ChipSimulator::run() {
  for (unsigned c = 0; c < chip_.cores; ++c) {
    const Work w = work_.start(c);
    const double cost = workCost(w);
    stats_[c].rules += w.rules;
    stats_[c].facts += w.facts;
    const double total = cost + send(c, 0, cost, false);
    stats_[c].busyNs += ns(total);
    if (!timelines_.empty()) timelines_[c].run(0, ns(total), w.facts, work_.queued(c), 0);
    wake(c, ns(total));
  }
  simcore::Event e;
  while (!work_.stopped() && queue_.popUntil(simcore::kTimeInfinity, e)) {
    end_ = std::max(end_, e.time);
    if (e.kind == kRun)
      runCore(e.block, e.time);
    else
      arrive(e.arg, e.time);
  }
  for (unsigned c = 0; c < chip_.cores; ++c) {
    if (core_[c].idleSince < end_ && !core_[c].scheduled) {
      stats_[c].idleNs += end_ - core_[c].idleSince;
      if (!timelines_.empty()) timelines_[c].idle(core_[c].idleSince, end_);
    }
    if (!timelines_.empty()) timelines_[c].finish();
  }
}

void ChipSimulator::wake(unsigned core, simcore::SimTime at) {
  core_[core].scheduled = true;
  queue_.schedule(at, simcore::PriorityClass::Program, core, kRun, 0, 0);
}

void ChipSimulator::runCore(unsigned c, simcore::SimTime now) {
  Core& core = core_[c];
  core.scheduled = false;
  if (barrier_) return arriveAtBarrier(c, now);
  Work w;
  if (!work_.runNext(c, w)) {
    // Out of nodes: what waits for other cores goes now, and facts taken in while there was no
    // node to run still cost.
    const double owed = core.owedNs + send(c, now, core.owedNs, true);
    core.owedNs = 0;
    if (owed > 0) {
      const simcore::SimTime t = ns(owed);
      stats_[c].busyNs += t;
      if (!timelines_.empty()) timelines_[c].run(now, now + t, 0, 0, 0);
      return wake(c, now + t);
    }
    return goIdle(c, now);
  }
  const CoreCosts& k = chip_.costs;
  double cost = k.nodeRun + workCost(w) + core.owedNs;
  core.owedNs = 0;
  if (chip_.cores > 1 && k.contention > 0)  // the cores busy now, this one included
    cost *= 1 + k.contention * double(chip_.cores - idleCores_ - 1) / double(chip_.cores - 1);
  cost += send(c, now, cost, false);
  const simcore::SimTime done = now + ns(cost);
  CoreStats& s = stats_[c];
  ++s.nodeRuns;
  s.rules += w.rules;
  s.facts += w.facts;
  s.busyNs += done - now;
  const std::size_t queued = work_.queued(c);
  if (!timelines_.empty()) timelines_[c].run(now, done, w.facts, queued);
  wake(c, done);
  if (work_.movesRequested())
    requestRebalance(done, true);
  else if (chip_.stealing && idleCores_ != 0 && queued >= kStealableQueue)
    requestRebalance(done, false);
}

// The batches of the run that took `runNs` from `now`: they leave when it ends. Returns the
// sending cost, which the run pays too.
double ChipSimulator::send(unsigned c, simcore::SimTime now, double runNs, bool force) {
  outgoing_.clear();
  work_.takeOutgoing(c, outgoing_, force);
  double cost = 0;
  for (const Batch& b : outgoing_)
    cost += double(b.facts) * chip_.costs.send + double(b.bytes) * chip_.costs.byte;
  const simcore::SimTime leave = now + ns(runNs + cost);
  for (const Batch& b : outgoing_) {
    const simcore::SimTime arrival = leave + ns(double(hops(chip_, c, b.to)) * chip_.hopLatency);
    std::uint64_t slot;
    if (freeSlots_.empty()) {
      slot = inFlight_.size();
      inFlight_.push_back({});
    } else {
      slot = freeSlots_.back();
      freeSlots_.pop_back();
    }
    inFlight_[slot] = {b.to, b.facts, b.bytes, b.handle, arrival, false};
    queue_.schedule(arrival, simcore::PriorityClass::Message, b.to, kArrival, 0, slot);
    stats_[c].factsOut += b.facts;
    ++stats_[c].batchesOut;
  }
  return cost;
}

void ChipSimulator::arrive(std::uint64_t slot, simcore::SimTime now) {
  InFlight& f = inFlight_[slot];
  const bool delivered = f.delivered;  // already, by a rebalance's drain
  freeSlots_.push_back(slot);
  if (delivered) return;
  const unsigned c = f.to;
  work_.deliver(c, f.handle);
  stats_[c].factsIn += f.facts;
  if (!timelines_.empty()) timelines_[c].factsIn(f.facts);
  core_[c].owedNs += receiveCost(f);
  Core& core = core_[c];
  if (core.scheduled || core.inBarrier) return;
  // The core was idle: it wakes now.
  --idleCores_;
  stats_[c].idleNs += now - core.idleSince;
  if (!timelines_.empty()) timelines_[c].idle(core.idleSince, now);
  wake(c, now);
}

void ChipSimulator::goIdle(unsigned c, simcore::SimTime now) {
  core_[c].idleSince = now;
  ++idleCores_;
  if (chip_.stealing && someoneCanGive(c)) requestRebalance(now, false);
}

bool ChipSimulator::someoneCanGive(unsigned except) const {
  for (unsigned c = 0; c < chip_.cores; ++c)
    if (c != except && work_.queued(c) >= kStealableQueue) return true;
  return false;
}

// ---- the rebalancing barrier ----

void ChipSimulator::requestRebalance(simcore::SimTime now, bool forced) {
  if (barrier_ || (!forced && now < nextRebalance_)) return;
  barrier_ = true;
  inBarrier_ = 0;
  // Idle cores are in the barrier at once; busy ones arrive when their run ends.
  for (unsigned c = 0; c < chip_.cores; ++c) {
    if (core_[c].scheduled) continue;
    --idleCores_;
    stats_[c].idleNs += now - core_[c].idleSince;
    if (!timelines_.empty()) timelines_[c].idle(core_[c].idleSince, now);
    arriveAtBarrier(c, now);
  }
}

void ChipSimulator::arriveAtBarrier(unsigned c, simcore::SimTime now) {
  core_[c].owedNs += send(c, now, 0, true);  // what waits goes out first (the drain delivers it); paid later
  core_[c].inBarrier = true;
  core_[c].barrierSince = now;
  if (++inBarrier_ == chip_.cores) completeBarrier(now);
}

void ChipSimulator::completeBarrier(simcore::SimTime now) {
  // Drain: what is in transit arrives before anything moves (its event finds it delivered).
  simcore::SimTime drained = now;
  for (InFlight& f : inFlight_) {
    if (f.delivered || f.arrival < now) continue;  // taken in already (arrival < now: slot free)
    drained = std::max(drained, f.arrival);
    f.delivered = true;
    work_.deliver(f.to, f.handle);
    stats_[f.to].factsIn += f.facts;
    core_[f.to].owedNs += receiveCost(f);
  }
  std::vector<std::uint64_t> takenBefore(chip_.cores);
  for (unsigned c = 0; c < chip_.cores; ++c) takenBefore[c] = stats_[c].nodesTaken;
  // A moving node's records (its facts go as a crossing fact's do) are packed while every core
  // waits, then unpacked by the taker alone while the others go on (vm/threads' worker.cpp, phase
  // 4). Moves asked for by set-cpu are not told apart by taker: every core waits for them both ways.
  std::uint64_t bytes = 0;
  const std::size_t requested = work_.applyRequestedMoves(bytes);
  const std::uint64_t requestedBytes = bytes;
  std::vector<std::uint64_t> takenBytes(chip_.cores, 0);
  const std::size_t moved = requested + (chip_.stealing ? stealPlan(now, bytes, takenBytes) : 0);
  const double shared = chip_.costs.rebalance + double(moved) * chip_.costs.nodeMoved +
                        double(bytes + requestedBytes) * chip_.costs.movedByte;
  double longest = shared;
  ++rebalances_;
  for (unsigned c = 0; c < chip_.cores; ++c) {
    const double cost = shared + double(takenBytes[c]) * chip_.costs.movedByte;
    longest = std::max(longest, cost);
    const simcore::SimTime resume = drained + ns(cost);
    Core& core = core_[c];
    core.inBarrier = false;
    ++stats_[c].rebalances;
    stats_[c].stealNs += resume - core.barrierSince;
    if (!timelines_.empty())
      timelines_[c].steal(core.barrierSince, resume, stats_[c].nodesTaken - takenBefore[c]);
    wake(c, resume);  // a core with nothing to do goes idle again at once
  }
  barrier_ = false;
  const simcore::SimTime resume = drained + ns(longest);
  nextRebalance_ = resume + StealPolicy::nextRebalanceAfter(longest);
  windowStart_ = resume;
  for (unsigned c = 0; c < chip_.cores; ++c) idleAtWindow_[c] = stats_[c].idleNs;
}

// The i-th most loaded core gives to the i-th least loaded (StealPolicy says how many nodes).
std::size_t ChipSimulator::stealPlan(simcore::SimTime now, std::uint64_t& bytes,
                                     std::vector<std::uint64_t>& takenBytes) {
  std::vector<unsigned> order(chip_.cores);
  std::vector<std::size_t> load(chip_.cores);
  std::vector<double> idle(chip_.cores);
  std::iota(order.begin(), order.end(), 0u);
  const double window = double(now - windowStart_);
  for (unsigned c = 0; c < chip_.cores; ++c) {
    load[c] = work_.queued(c);
    idle[c] = StealPolicy::idleShare(
        double(stats_[c].idleNs - idleAtWindow_[c] + (now - core_[c].barrierSince)), window);
  }
  std::stable_sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return load[a] > load[b]; });
  std::size_t moved = 0;
  for (std::size_t i = 0; i < order.size() / 2; ++i) {
    const unsigned giver = order[i], taker = order[order.size() - 1 - i];
    const std::size_t count = StealPolicy::nodesToGive(load[giver], load[taker], idle[giver], idle[taker]);
    if (count == 0) continue;
    const std::uint64_t before = bytes;
    const std::size_t n = work_.moveNodes(giver, taker, count, bytes);
    takenBytes[taker] += bytes - before;
    stats_[giver].nodesGiven += n;
    stats_[taker].nodesTaken += n;
    moved += n;
  }
  return moved;
}

void ChipSimulator::writeProfile(std::ostream& out) const {
  std::vector<support::ProfileLane> lanes;
  for (unsigned c = 0; c < chip_.cores; ++c)
    lanes.push_back({"core " + std::to_string(c), timelines_.empty() ? nullptr : &timelines_[c].spans()});
  support::writeProfileTrace(out, "vsim multicore " + std::to_string(chip_.cores) + " cores", lanes);
}

}  // namespace multicore
