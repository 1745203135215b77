#define BOOST_TEST_MODULE simcore_fingerprint
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <vector>

#include "simcore/stats.hpp"
#include "test_support.hpp"

using namespace simcore;

namespace {

constexpr std::uint32_t kBlocks = 120;
constexpr std::int32_t kSide = 16;

std::unique_ptr<Simulation> world(std::uint64_t seed, FesKind fes = FesKind::Heap) {
  SimulationConfig cfg;
  cfg.seed = seed;
  cfg.fes = fes;
  return testsupport::makeWalkWorld(kBlocks, kSide, cfg);
}

struct Outcome {
  std::uint64_t fingerprint;
  std::uint64_t events;
  std::uint64_t messages;
  std::uint64_t motions;
  SimTime end;
  std::vector<Cell> cells;
  std::vector<std::uint32_t> colors;
};

Outcome outcome(const Simulation& sim) {
  Outcome o{sim.fingerprint(),
            sim.statistics().eventsProcessed,
            sim.statistics().messagesSent,
            sim.statistics().motionsStarted,
            sim.now(),
            {},
            {}};
  for (const Block& b : sim.world().blocks()) {
    o.cells.push_back(b.cell);
    o.colors.push_back(b.color);
  }
  return o;
}

void checkSame(const Outcome& a, const Outcome& b) {
  BOOST_CHECK_EQUAL(a.fingerprint, b.fingerprint);
  BOOST_CHECK_EQUAL(a.events, b.events);
  BOOST_CHECK_EQUAL(a.messages, b.messages);
  BOOST_CHECK_EQUAL(a.motions, b.motions);
  BOOST_CHECK_EQUAL(a.end, b.end);
  BOOST_CHECK(a.cells == b.cells);
  BOOST_CHECK(a.colors == b.colors);
}

Outcome uninterrupted(std::uint64_t seed) {
  auto sim = world(seed);
  BOOST_CHECK(sim->runUntilEmpty() == RunStatus::Idle);
  return outcome(*sim);
}

}  // namespace

BOOST_AUTO_TEST_CASE(fingerprint_hashes_time_block_and_kind_in_order) {
  Fingerprint a, b, c, d;
  a.add(10, 1, EventKind::Timer);
  a.add(20, 2, EventKind::Message);
  b.add(10, 1, EventKind::Timer);
  b.add(20, 2, EventKind::Message);
  c.add(20, 2, EventKind::Message);  // same events, other order
  c.add(10, 1, EventKind::Timer);
  d.add(10, 1, EventKind::Timer);
  d.add(20, 2, EventKind::Tap);  // other kind
  BOOST_CHECK_EQUAL(a.value(), b.value());
  BOOST_CHECK_NE(a.value(), c.value());
  BOOST_CHECK_NE(a.value(), d.value());
  BOOST_CHECK_NE(a.value(), Fingerprint{}.value());
}

BOOST_AUTO_TEST_CASE(same_seed_same_fingerprint_different_seed_different) {
  // Two simulations alive at once in one process, run interleaved slice by slice.
  auto s1 = world(1), s2 = world(1), s3 = world(2);
  for (SimTime t = kSecond; s1->pendingEvents() || s2->pendingEvents() || t <= kSecond; t += kSecond) {
    s1->runUntil(t);
    s2->runUntil(t);
    BOOST_REQUIRE_EQUAL(s1->fingerprint(), s2->fingerprint());
  }
  s3->runUntilEmpty();
  const Outcome a = outcome(*s1), b = outcome(*s2), c = outcome(*s3);
  BOOST_TEST_MESSAGE("seed 1: " << a.events << " events, fingerprint " << std::hex << a.fingerprint);
  BOOST_CHECK_GT(a.events, 3000u);
  BOOST_CHECK_GT(a.motions, 200u);
  BOOST_CHECK_GT(a.messages, 50u);
  checkSame(a, b);
  BOOST_CHECK_NE(a.fingerprint, c.fingerprint);
  BOOST_CHECK(a.cells != c.cells);
  // Same seed, other future-event set: the same run (run to the end, without the final advance of
  // now() to the slice limit).
  auto s4 = world(1, FesKind::Calendar);
  s4->runUntilEmpty();
  checkSame(uninterrupted(1), outcome(*s4));
  BOOST_CHECK_EQUAL(s4->fingerprint(), a.fingerprint);
}

BOOST_AUTO_TEST_CASE(run_until_stops_at_T_and_resumes_to_the_same_end) {
  const Outcome whole = uninterrupted(4);
  BOOST_REQUIRE_GT(whole.end, 5 * kSecond);
  for (SimTime T : {SimTime(0), 1234567 * kNanosecond, 2 * kSecond, 5 * kSecond + 1}) {
    BOOST_TEST_CONTEXT("T = " << T) {
      auto sim = world(4);
      BOOST_CHECK(sim->runUntil(T) == RunStatus::TimeLimit);
      BOOST_CHECK_EQUAL(sim->now(), T);
      BOOST_CHECK_GT(sim->pendingEvents(), 0u);
      BOOST_CHECK_NE(sim->fingerprint(), whole.fingerprint);
      BOOST_CHECK(sim->runUntil(T) == RunStatus::TimeLimit);  // again: nothing to do, no change
      BOOST_CHECK_EQUAL(sim->now(), T);
      sim->runUntilEmpty();
      checkSame(whole, outcome(*sim));
    }
  }
  // Many small slices, and a limit past the end: now() ends at the limit, the events are the same.
  auto sim = world(4);
  for (SimTime t = 0; t < whole.end; t += 37 * kMillisecond) {
    sim->runUntil(t);
    BOOST_REQUIRE_EQUAL(sim->now(), t);
  }
  const SimTime past = whole.end + kSecond;
  BOOST_CHECK(sim->runUntil(past) == RunStatus::Idle);
  BOOST_CHECK_EQUAL(sim->now(), past);
  BOOST_CHECK_EQUAL(sim->fingerprint(), whole.fingerprint);
  BOOST_CHECK_EQUAL(sim->statistics().eventsProcessed, whole.events);
}

BOOST_AUTO_TEST_CASE(step_and_event_limits_give_the_same_run) {
  const Outcome whole = uninterrupted(6);
  auto sim = world(6);
  std::uint64_t steps = 0;
  SimTime last = 0;
  while (sim->step()) {
    ++steps;
    BOOST_REQUIRE_GE(sim->now(), last);
    last = sim->now();
    BOOST_REQUIRE_EQUAL(sim->statistics().eventsProcessed, steps);
  }
  BOOST_CHECK_EQUAL(steps, whole.events);
  BOOST_CHECK(!sim->step());
  checkSame(whole, outcome(*sim));

  auto batched = world(6);
  while (batched->run(kTimeInfinity, 1000) == RunStatus::EventLimit) {
  }
  checkSame(whole, outcome(*batched));
}
