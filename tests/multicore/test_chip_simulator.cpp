// The simulated chip of the multicore target (targets/multicore) with made-up workloads whose
// timings can be worked out by hand.
#define BOOST_TEST_MODULE chip_simulator
#include <boost/test/unit_test.hpp>
#include <deque>
#include <sstream>

#include "multicore/chip_simulator.hpp"

using namespace multicore;

namespace {

// A unit of work: a node run with `rules` rule firings and `facts` facts, sending `sendFacts`
// facts (10 bytes each) to core `sendTo` (none when sendFacts is 0). A batch that arrives queues `spawn`
// units of one rule and one fact on its core.
struct Unit {
  std::uint64_t rules = 1, facts = 1;
  unsigned sendTo = 0;
  std::uint64_t sendFacts = 0;
};

class FakeWorkload : public CoreWorkload {
 public:
  explicit FakeWorkload(unsigned cores) : queue(cores), pending(cores), arrived(cores, 0) {}
  Work start(unsigned) override { return {}; }
  bool runNext(unsigned core, Work& work) override {
    if (queue[core].empty()) return false;
    const Unit u = queue[core].front();
    queue[core].pop_front();
    work = {u.rules, u.facts};
    if (u.sendFacts) pending[core].push_back({u.sendTo, u.sendFacts, 10 * u.sendFacts, u.sendFacts});
    return true;
  }
  std::size_t queued(unsigned core) const override { return queue[core].size(); }
  void takeOutgoing(unsigned core, std::vector<Batch>& out, bool) override {
    out.insert(out.end(), pending[core].begin(), pending[core].end());
    pending[core].clear();
  }
  void deliver(unsigned core, std::uint64_t handle) override {
    arrived[core] += handle;  // the handle is the fact count here
    for (unsigned i = 0; i < spawn; ++i) queue[core].push_back({});
  }
  std::size_t moveNodes(unsigned from, unsigned to, std::size_t count, std::uint64_t& bytes) override {
    std::size_t moved = 0;
    for (; moved < count && !queue[from].empty(); ++moved) {
      queue[to].push_back(queue[from].back());
      queue[from].pop_back();
      bytes += 100;
    }
    return moved;
  }
  bool movesRequested() const override { return false; }
  std::size_t applyRequestedMoves(std::uint64_t&) override { return 0; }
  bool stopped() const override { return false; }

  std::vector<std::deque<Unit>> queue;
  std::vector<std::vector<Batch>> pending;
  std::vector<std::uint64_t> arrived;
  unsigned spawn = 1;
};

ChipSpec chipOf(unsigned cores, bool stealing = false) {
  ChipSpec c;
  c.cores = cores;
  c.stealing = stealing;
  c.hopLatency = 40;
  c.costs.nodeRun = 100;
  c.costs.rule = 10;
  c.costs.fact = 1;
  c.costs.send = 7;
  c.costs.receive = 3;
  c.costs.byte = 0;
  c.costs.rebalance = 5000;
  c.costs.nodeMoved = 50;
  c.costs.movedByte = 0;
  c.costs.contention = 0;
  return c;
}

}  // namespace

BOOST_AUTO_TEST_CASE(hops_follow_the_topology) {
  ChipSpec c = chipOf(16);
  c.topology = Topology::Mesh;  // 4 x 4, row-major
  BOOST_TEST(meshWidth(16) == 4u);
  BOOST_TEST(meshWidth(5) == 3u);
  BOOST_TEST(hops(c, 0, 15) == 6u);
  BOOST_TEST(hops(c, 5, 6) == 1u);
  BOOST_TEST(hops(c, 1, 13) == 3u);
  BOOST_TEST(hops(c, 7, 7) == 0u);
  c.topology = Topology::Ring;
  BOOST_TEST(hops(c, 0, 15) == 1u);
  BOOST_TEST(hops(c, 0, 8) == 8u);
  BOOST_TEST(hops(c, 3, 12) == 7u);
  c.topology = Topology::Full;
  BOOST_TEST(hops(c, 0, 15) == 1u);
  BOOST_TEST(hops(c, 4, 4) == 0u);
  BOOST_TEST((parseTopology("ring") == Topology::Ring));
  BOOST_TEST(!parseTopology("torus").has_value());
}

BOOST_AUTO_TEST_CASE(independent_cores_take_the_time_of_their_work) {
  FakeWorkload w(4);
  for (unsigned c = 0; c < 4; ++c)
    for (unsigned i = 0; i < 10 + c; ++i) w.queue[c].push_back({2, 3, 0, 0});
  ChipSimulator sim(chipOf(4), w);
  sim.run();
  const std::int64_t unit = 100 + 2 * 10 + 3 * 1;
  BOOST_TEST(sim.endTime() == 13 * unit);  // the most loaded core decides
  for (unsigned c = 0; c < 4; ++c) {
    BOOST_TEST(sim.cores()[c].nodeRuns == 10u + c);
    BOOST_TEST(sim.cores()[c].busyNs == (10 + c) * unit);
    BOOST_TEST(sim.cores()[c].idleNs == (3 - c) * unit);
  }
}

BOOST_AUTO_TEST_CASE(a_fact_crosses_the_mesh_and_is_paid_for_at_both_ends) {
  FakeWorkload w(4);  // 2 x 2 mesh: core 0 to core 3 is two hops
  w.queue[0].push_back({1, 1, 3, 5});
  ChipSpec chip = chipOf(4);
  chip.costs.byte = 0.25;  // 50 bytes: 12.5 ns at each end
  ChipSimulator sim(chip, w);
  sim.run();
  const double sendRun = 100 + 10 + 1 + 5 * 7 + 12.5;                 // the run, its 5 sends and their bytes
  const std::int64_t arrival = std::int64_t(sendRun + 0.5) + 2 * 40;  // two hops
  const double receiveRun = 100 + 10 + 1 + 5 * 3 + 12.5;  // the spawned unit, the 5 receives, the bytes
  BOOST_TEST(w.arrived[3] == 5u);
  BOOST_TEST(sim.endTime() == arrival + std::int64_t(receiveRun + 0.5));
  BOOST_TEST(sim.cores()[0].factsOut == 5u);
  BOOST_TEST(sim.cores()[3].factsIn == 5u);
  BOOST_TEST(sim.cores()[3].busyNs == std::int64_t(receiveRun + 0.5));
  BOOST_TEST(sim.cores()[3].idleNs == arrival);
}

BOOST_AUTO_TEST_CASE(idle_cores_steal_and_finish_sooner) {
  auto endWith = [](bool stealing, std::uint64_t& taken) {
    FakeWorkload w(2);
    for (int i = 0; i < 400; ++i) w.queue[0].push_back({20, 20, 0, 0});
    ChipSimulator sim(chipOf(2, stealing), w);
    sim.run();
    taken = sim.cores()[1].nodesTaken;
    BOOST_TEST(sim.cores()[0].nodeRuns + sim.cores()[1].nodeRuns == 400u);
    return sim.endTime();
  };
  std::uint64_t takenStatic = 0, takenStealing = 0;
  const auto staticEnd = endWith(false, takenStatic);
  const auto stealingEnd = endWith(true, takenStealing);
  BOOST_TEST(staticEnd == 400 * (100 + 20 * 10 + 20));
  BOOST_TEST(takenStatic == 0u);
  BOOST_TEST(takenStealing >= 150u);
  // Core 1 finds nothing at time 0 and asks; core 0 joins when its first unit ends (320 ns); one
  // rebalance moves 199 of its 399 queued units (5000 + 199 x 50 ns); then 200 units each.
  BOOST_TEST(stealingEnd == 320 + 5000 + 199 * 50 + 200 * 320);
}

BOOST_AUTO_TEST_CASE(a_moving_node_pays_for_its_bytes_at_both_ends_and_only_the_taker_unpacks) {
  FakeWorkload w(2);
  for (int i = 0; i < 400; ++i) w.queue[0].push_back({20, 20, 0, 0});
  ChipSpec chip = chipOf(2, true);
  chip.costs.movedByte = 0.5;
  chip.costs.byte = 1000;  // the crossing facts' rate: not the moves'
  ChipSimulator sim(chip, w);
  sim.run();
  // As above, and the rebalance carries 199 units of 100 bytes, 0.5 ns a byte at each end: both
  // cores wait while they are packed (from 320 ns on), then core 0 goes on with its 200 units
  // while core 1 (in the barrier since 0) unpacks its 199 and runs them, and ends last.
  const std::uint64_t packed = 5000 + 199 * 50 + 199 * 100 / 2, unpacked = 199 * 100 / 2;
  BOOST_TEST(sim.cores()[0].stealNs == packed);
  BOOST_TEST(sim.cores()[1].stealNs == 320 + packed + unpacked);
  BOOST_TEST(sim.endTime() == 320 + packed + unpacked + 199 * 320);
}

BOOST_AUTO_TEST_CASE(runs_are_deterministic_and_profiles_have_one_lane_per_core) {
  auto once = [](std::string& profile) {
    FakeWorkload w(3);
    w.spawn = 2;
    for (unsigned i = 0; i < 50; ++i) w.queue[i % 3].push_back({1, 1, (i + 1) % 3, i % 4});
    ChipSimulator sim(chipOf(3, true), w, true);
    // Spawning stops by itself: only units with sendFacts > 0 send, and spawned units send nothing.
    sim.run();
    for (unsigned c = 0; c < 3; ++c) {  // the profile's spans add up to the core's statistics
      std::int64_t run = 0, idle = 0, steal = 0;
      for (const support::ProfileSpan& s : sim.spans(c))
        (s.kind == support::ProfileSpan::Kind::Run    ? run
         : s.kind == support::ProfileSpan::Kind::Idle ? idle
                                                      : steal) += s.endNs - s.beginNs;
      BOOST_TEST(run == sim.cores()[c].busyNs);
      BOOST_TEST(idle == sim.cores()[c].idleNs);
      BOOST_TEST(steal == sim.cores()[c].stealNs);
      BOOST_TEST(run + idle + steal == sim.endTime());
    }
    std::ostringstream out;
    sim.writeProfile(out);
    profile = out.str();
    return sim.endTime();
  };
  std::string a, b;
  BOOST_TEST(once(a) == once(b));
  BOOST_TEST(a == b);
  BOOST_TEST(a.find("\"name\":\"vsim multicore 3 cores\"") != std::string::npos);
  for (const char* lane : {"\"core 0\"", "\"core 1\"", "\"core 2\""})
    BOOST_TEST(a.find(lane) != std::string::npos);
  BOOST_TEST(a.find("\"cat\":\"run\"") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_chip_needs_a_core) {
  FakeWorkload w(1);
  BOOST_CHECK_THROW(ChipSimulator(chipOf(0), w), std::invalid_argument);
}
