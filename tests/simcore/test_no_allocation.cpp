// The kernel's hot paths allocate nothing per event in the steady state: after a warm-up, a long
// stretch of a busy run (motions, timers, messages, neighbor changes) performs no heap allocation,
// whichever future-event set is used. Counted by replacing the global operator new in this test.
#define BOOST_TEST_MODULE no_allocation
#include <boost/test/unit_test.hpp>

#include "../common/counting_new.hpp"
#include "simcore/blockcode.h"
#include "simcore/simulation.hpp"
#include "smartblocks/smartblocks.hpp"

extern "C" const vs_blockcode* brownian_flood_variant(int epidemic);  // examples/c/brownian_flood.c

namespace {

// Wander at random like brownian-flood, and on every wake-up also send a 4-byte message to every
// neighbor, so message slots, link state, motions and timers all churn.
void wake(vs_ctx* c) { vs_set_timer(c, vs_time(vs_random_below(c, 1000000001u)), 1); }
void onStart(vs_ctx* c) { wake(c); }
void onEvent(vs_ctx* c, const vs_event* ev) {
  if (ev->kind == VS_EV_TIMER) {
    const std::uint32_t hello = c->block;
    vs_send_all(c, &hello, sizeof hello, 0);
    if (vs_move(c, int(vs_random_below(c, 4))) != VS_OK) wake(c);
  } else if (ev->kind == VS_EV_MOTION_END) {
    wake(c);
  }
}
const vs_blockcode kWanderer = {VS_ABI_VERSION, "wanderer", 0, onStart, onEvent, nullptr, nullptr};

void checkSteadyStateAllocations(simcore::FesKind fes, const vs_blockcode* code = &kWanderer) {
  simcore::SimulationConfig cfg;
  cfg.fes = fes;
  cfg.seed = 7;
  const std::int32_t side = 60;
  simcore::Simulation sim(targets::smartBlocksTarget(), simcore::GridSize{side, side, 1}, cfg);
  for (std::int32_t y = 0; y < side; ++y)
    for (std::int32_t x = 0; x < side; ++x)
      if ((x * 7 + y * 13) % 2 == 0) sim.addBlock(simcore::Cell{x, y, 0});
  sim.setBlockCode(code);

  sim.runUntil(60 * simcore::kSecond);  // warm-up: pools and queues reach their working sizes
  const std::uint64_t eventsBefore = sim.statistics().eventsProcessed;
  const std::uint64_t before = testcommon::allocations();
  sim.runUntil(120 * simcore::kSecond);
  const std::uint64_t during = testcommon::allocations() - before;
  const std::uint64_t events = sim.statistics().eventsProcessed - eventsBefore;

  BOOST_TEST_MESSAGE(simcore::fesKindName(fes) << ": " << events << " events, " << during << " allocations");
  BOOST_CHECK_GT(events, 300000u);
  BOOST_CHECK_GT(sim.statistics().messagesSent, 100000u);
  if (code == &kWanderer) BOOST_CHECK_GT(sim.statistics().messagesDropped, 0u);  // its sends race motions
  // The run is deterministic, so this is exact: pools, rings and buckets reached their working sizes
  // in the warm-up. (This world is small enough that every array goes through operator new.)
  BOOST_CHECK_EQUAL(during, 0u);
}

}  // namespace

BOOST_AUTO_TEST_CASE(heap_steady_state_allocates_nothing_per_event) {
  checkSteadyStateAllocations(simcore::FesKind::Heap);
}
BOOST_AUTO_TEST_CASE(calendar_steady_state_allocates_nothing_per_event) {
  checkSteadyStateAllocations(simcore::FesKind::Calendar);
}
BOOST_AUTO_TEST_CASE(ladder_steady_state_allocates_nothing_per_event) {
  checkSteadyStateAllocations(simcore::FesKind::Ladder);
}
BOOST_AUTO_TEST_CASE(b1_epidemic_steady_state_allocates_nothing_per_event) {
  // B1 --epidemic: informed blocks send on every new contact, so messages keep flowing after the
  // whole world has the information.
  checkSteadyStateAllocations(simcore::kDefaultFes, brownian_flood_variant(1));
}
