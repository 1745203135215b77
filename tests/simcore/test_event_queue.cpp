#define BOOST_TEST_MODULE simcore_event_queue
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <iterator>
#include <set>
#include <utility>
#include <vector>

#include "simcore/calendar_fes.hpp"
#include "simcore/event_queue.hpp"
#include "simcore/heap_fes.hpp"
#include "simcore/rng.hpp"
#include "test_support.hpp"

using namespace simcore;

namespace {

// Every future-event set the kernel offers: they must all give the same order.
const FesKind kKinds[] = {FesKind::Heap, FesKind::Calendar, FesKind::Ladder};

// Deterministic random numbers for the tests (the kernel's own generator, a fixed stream).
struct Rand {
  std::uint64_t s;
  explicit Rand(std::uint64_t seed) : s(BlockRng::initialState(seed, 99)) {}
  std::uint32_t below(std::uint32_t n) { return BlockRng::below(s, 99, n); }
};

Event makeEvent(SimTime t, unsigned cls, std::uint64_t seq) {
  Event e;
  e.time = t;
  e.order = (std::uint64_t(cls) << Event::kSequenceBits) | seq;
  e.block = std::uint32_t(seq);
  e.kind = EventKind::Timer;
  e.arg = seq;
  return e;
}

using Key = std::pair<SimTime, std::uint64_t>;  // (time, order): the total order of the kernel
Key keyOf(const Event& e) { return {e.time, e.order}; }

// Times with many ties: a few distinct values, sometimes far ahead.
SimTime tiedTime(Rand& r, SimTime base) {
  switch (r.below(4)) {
    case 0:
      return base;
    case 1:
      return base + SimTime(r.below(8)) * 1000;
    case 2:
      return base + SimTime(r.below(64)) * 250;
    default:
      return base + SimTime(r.below(1000)) * 1000003;
  }
}

// Pops everything, checking each pop against the reference and returning the popped keys.
std::vector<Key> drain(FutureEventSet& fes, std::set<Key>& ref) {
  std::vector<Key> out;
  while (const Event* e = fes.peek()) {
    BOOST_REQUIRE(!ref.empty());
    BOOST_REQUIRE_MESSAGE(keyOf(*e) == *ref.begin(), fes.name() << ": popped (" << e->time << ", " << e->order
                                                                << ") but expected (" << ref.begin()->first
                                                                << ", " << ref.begin()->second << ")");
    out.push_back(keyOf(*e));
    // peekAhead is only a hint, but when it answers it must be the k-th next event.
    if (out.size() % 97 == 1) {
      for (std::size_t k : {0u, 1u, 3u, 9u}) {
        const Event* a = fes.peekAhead(k);
        if (!a || k >= ref.size()) continue;
        BOOST_REQUIRE_MESSAGE(keyOf(*a) == *std::next(ref.begin(), long(k)),
                              fes.name() << ": peekAhead(" << k << ")");
      }
    }
    ref.erase(ref.begin());
    fes.pop();
  }
  BOOST_CHECK(ref.empty());
  BOOST_CHECK_EQUAL(fes.size(), 0u);
  return out;
}

// Hold model: pop one event, push 0..2 events not earlier than it, with peeks in between.
std::vector<Key> holdModel(FesKind kind, std::uint64_t seed, int steps) {
  auto fes = makeFutureEventSet(kind);
  std::set<Key> ref;
  Rand r(seed);
  std::uint64_t seq = 0;
  for (int i = 0; i < 2000; ++i) {
    const Event e = makeEvent(tiedTime(r, 0), r.below(4), seq++);
    fes->push(e);
    ref.insert(keyOf(e));
  }
  std::vector<Key> popped;
  for (int i = 0; i < steps && fes->peek(); ++i) {
    const Event* e = fes->peek();
    BOOST_REQUIRE(keyOf(*e) == *ref.begin());
    const SimTime now = e->time;
    popped.push_back(keyOf(*e));
    ref.erase(ref.begin());
    fes->pop();
    const unsigned pushes = r.below(3) + (fes->size() < 500 ? 1 : 0);
    for (unsigned k = 0; k < pushes; ++k) {
      const Event n = makeEvent(tiedTime(r, now), r.below(4), seq++);
      fes->peek();  // a peek between pushes must not hide a later, earlier push
      fes->push(n);
      ref.insert(keyOf(n));
    }
    BOOST_REQUIRE_EQUAL(fes->size(), ref.size());
  }
  auto rest = drain(*fes, ref);
  popped.insert(popped.end(), rest.begin(), rest.end());
  return popped;
}

}  // namespace

BOOST_AUTO_TEST_CASE(fes_pops_random_tied_events_in_time_class_sequence_order) {
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      auto fes = makeFutureEventSet(kind);
      std::set<Key> ref;
      Rand r(1);
      for (std::uint64_t seq = 0; seq < 20000; ++seq) {
        const Event e = makeEvent(tiedTime(r, 5000), r.below(4), seq);
        fes->push(e);
        ref.insert(keyOf(e));
      }
      BOOST_CHECK_EQUAL(fes->size(), 20000u);
      const auto popped = drain(*fes, ref);
      BOOST_CHECK_EQUAL(popped.size(), 20000u);
      BOOST_CHECK(std::is_sorted(popped.begin(), popped.end()));
    }
  }
}

BOOST_AUTO_TEST_CASE(fes_equal_time_and_class_is_fifo) {
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      auto fes = makeFutureEventSet(kind);
      for (std::uint64_t seq = 0; seq < 1000; ++seq) fes->push(makeEvent(777, 2, seq));
      std::uint64_t expect = 0;
      while (const Event* e = fes->peek()) {
        BOOST_REQUIRE_EQUAL(e->sequence(), expect);
        ++expect;
        fes->pop();
      }
      BOOST_CHECK_EQUAL(expect, 1000u);
    }
  }
}

BOOST_AUTO_TEST_CASE(fes_push_earlier_than_a_peeked_event_comes_first) {
  // A peek may move the calendar's "current day" forward; a later push of an earlier event must
  // still come out first (the kernel's queue peeks the future-event set while it drains the
  // current-time FIFO, whose handlers then schedule new events).
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      auto fes = makeFutureEventSet(kind);
      fes->push(makeEvent(1000000, 3, 0));
      BOOST_REQUIRE(fes->peek());
      BOOST_CHECK_EQUAL(fes->peek()->time, 1000000);
      fes->push(makeEvent(500, 3, 1));
      BOOST_REQUIRE(fes->peek());
      BOOST_CHECK_EQUAL(fes->peek()->time, 500);
      fes->pop();
      BOOST_REQUIRE(fes->peek());
      BOOST_CHECK_EQUAL(fes->peek()->time, 1000000);
      fes->pop();
      BOOST_CHECK(fes->peek() == nullptr);
      // Same without the peek: second push earlier than the first.
      fes->push(makeEvent(2000000, 3, 2));
      fes->push(makeEvent(1500, 3, 3));
      BOOST_REQUIRE(fes->peek());
      BOOST_CHECK_EQUAL(fes->peek()->time, 1500);
    }
  }
}

BOOST_AUTO_TEST_CASE(fes_hold_model_matches_reference_and_all_kinds_agree) {
  const auto heap = holdModel(FesKind::Heap, 11, 60000);
  // (Not globally sorted: an event pushed at the popped time in a lower class precedes it.)
  BOOST_CHECK_GT(heap.size(), 60000u);
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      const auto other = holdModel(kind, 11, 60000);
      BOOST_CHECK_EQUAL(heap.size(), other.size());
      BOOST_CHECK(heap == other);
    }
  }
}

BOOST_AUTO_TEST_CASE(calendar_resizes_keep_order) {
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      auto fes = makeFutureEventSet(kind);
      std::set<Key> ref;
      Rand r(5);
      std::uint64_t seq = 0;
      // Grow to 100k (many doublings), shrink to nothing (many halvings), twice, with different
      // time scales so the bucket width has to be re-estimated.
      for (SimTime scale : {SimTime(1), SimTime(1000000)}) {
        for (int i = 0; i < 100000; ++i) {
          const Event e = makeEvent(SimTime(r.below(50000)) * scale, r.below(4), seq++);
          fes->push(e);
          ref.insert(keyOf(e));
        }
        BOOST_CHECK_EQUAL(fes->size(), 100000u);
        drain(*fes, ref);
      }
      // Half-drain then refill at later times.
      for (int i = 0; i < 100000; ++i) {
        const Event e = makeEvent(SimTime(r.below(1000)) * 7, r.below(4), seq++);
        fes->push(e);
        ref.insert(keyOf(e));
      }
      for (int i = 0; i < 50000; ++i) {
        BOOST_REQUIRE(keyOf(*fes->peek()) == *ref.begin());
        ref.erase(ref.begin());
        fes->pop();
      }
      for (int i = 0; i < 50000; ++i) {
        const Event e = makeEvent(7000 + SimTime(r.below(100000)), r.below(4), seq++);
        fes->push(e);
        ref.insert(keyOf(e));
      }
      drain(*fes, ref);
    }
  }
}

BOOST_AUTO_TEST_CASE(event_queue_matches_reference_with_now_events) {
  std::vector<std::vector<Key>> runs;
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      EventQueue q(makeFutureEventSet(kind));
      std::set<Key> ref;
      Rand r(21);
      auto schedule = [&](SimTime t, unsigned cls) {
        const std::uint64_t order = (std::uint64_t(cls) << Event::kSequenceBits) | q.nextSequence();
        q.schedule(t, PriorityClass(cls), 0, EventKind::Timer, 0, 0);
        ref.insert({t, order});
      };
      for (int i = 0; i < 500; ++i) schedule(r.below(2) ? 0 : tiedTime(r, 0), r.below(4));
      std::vector<Key> popped;
      Event e;
      SimTime last = 0;
      while (q.popUntil(kTimeInfinity, e)) {
        BOOST_REQUIRE(!ref.empty());
        BOOST_REQUIRE_MESSAGE(keyOf(e) == *ref.begin(), "popped (" << e.time << ", " << e.order
                                                                   << ") expected (" << ref.begin()->first
                                                                   << ", " << ref.begin()->second << ")");
        ref.erase(ref.begin());
        BOOST_REQUIRE_EQUAL(q.now(), e.time);
        BOOST_REQUIRE_GE(e.time, last);
        last = e.time;
        popped.push_back(keyOf(e));
        if (popped.size() < 80000) {
          // Handlers schedule at the current time (FIFO) and later, in every class.
          const unsigned n = r.below(3) + (q.size() < 200 ? 1 : 0);
          for (unsigned k = 0; k < n; ++k)
            schedule(r.below(3) == 0 ? q.now() : tiedTime(r, q.now()), r.below(4));
        }
        BOOST_REQUIRE_EQUAL(q.size(), ref.size());
      }
      BOOST_CHECK(ref.empty());
      BOOST_CHECK_GT(popped.size(), 80000u);
      runs.push_back(popped);
    }
  }
  BOOST_REQUIRE_EQUAL(runs.size(), std::size(kKinds));
  for (std::size_t i = 1; i < runs.size(); ++i) BOOST_CHECK(runs[0] == runs[i]);
}

BOOST_AUTO_TEST_CASE(event_queue_now_fifo_interleaves_with_future_events_by_class) {
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      EventQueue q(makeFutureEventSet(kind));
      // Future events at t = 10, scheduled at time 0 (they sit in the future-event set).
      q.schedule(10, PriorityClass::Program, 1, EventKind::Timer, 0, 0);           // A
      q.schedule(10, PriorityClass::Topology, 2, EventKind::NeighborAdded, 0, 0);  // B
      q.schedule(10, PriorityClass::Message, 3, EventKind::Message, 0, 0);         // C
      q.schedule(20, PriorityClass::World, 9, EventKind::MotionEnd, 0, 0);         // later
      Event e;
      BOOST_REQUIRE(q.popUntil(kTimeInfinity, e));
      BOOST_CHECK_EQUAL(e.block, 2u);  // B: Topology first
      BOOST_CHECK_EQUAL(q.now(), 10);
      // While handling B at t = 10, events "now" in every class go to the current-time FIFO.
      q.schedule(10, PriorityClass::Program, 4, EventKind::Timer, 0, 0);    // D (after A: later sequence)
      q.schedule(10, PriorityClass::World, 5, EventKind::MotionEnd, 0, 0);  // E (first: World)
      q.schedule(10, PriorityClass::Message, 6, EventKind::Message, 0, 0);  // F (after C)
      q.schedule(10, PriorityClass::Topology, 7, EventKind::NeighborAdded, 0, 0);  // G
      std::vector<std::uint32_t> order;
      while (q.popUntil(kTimeInfinity, e)) order.push_back(e.block);
      const std::vector<std::uint32_t> expected = {5, 7, 3, 6, 1, 4, 9};
      BOOST_CHECK_EQUAL_COLLECTIONS(order.begin(), order.end(), expected.begin(), expected.end());
      BOOST_CHECK_EQUAL(q.now(), 20);
      BOOST_CHECK(q.empty());
    }
  }
}

BOOST_AUTO_TEST_CASE(event_queue_fifo_at_equal_time_and_class_and_limit) {
  for (FesKind kind : kKinds) {
    BOOST_TEST_CONTEXT("fes " << fesKindName(kind)) {
      EventQueue q(makeFutureEventSet(kind));
      for (std::uint32_t i = 0; i < 300; ++i)
        q.schedule(0, PriorityClass::Program, i, EventKind::Start, 0, 0);
      for (std::uint32_t i = 300; i < 600; ++i)
        q.schedule(50, PriorityClass::Message, i, EventKind::Message, 0, 0);
      Event e;
      std::uint32_t expect = 0;
      while (q.popUntil(49, e)) BOOST_REQUIRE_EQUAL(e.block, expect++);
      BOOST_CHECK_EQUAL(expect, 300u);
      BOOST_CHECK_EQUAL(q.size(), 300u);
      BOOST_CHECK_EQUAL(q.nextTime(), 50);
      while (q.popUntil(kTimeInfinity, e)) BOOST_REQUIRE_EQUAL(e.block, expect++);
      BOOST_CHECK_EQUAL(expect, 600u);
    }
  }
}

BOOST_AUTO_TEST_CASE(simulation_fingerprint_is_the_same_with_every_fes) {
  std::vector<std::uint64_t> prints;
  std::vector<std::uint64_t> events;
  for (FesKind kind : kKinds) {
    SimulationConfig cfg;
    cfg.seed = 3;
    cfg.fes = kind;
    auto sim = testsupport::makeWalkWorld(150, 18, cfg);
    BOOST_CHECK_EQUAL(sim->fesName(), fesKindName(kind));
    sim->runUntilEmpty();
    const Statistics& s = sim->statistics();
    BOOST_TEST_MESSAGE(fesKindName(kind) << ": " << s.eventsProcessed << " events, fingerprint " << std::hex
                                         << sim->fingerprint());
    BOOST_CHECK_GT(s.eventsProcessed, 3000u);
    BOOST_CHECK_GT(s.motionsStarted, 100u);
    BOOST_CHECK_GT(s.messagesSent, 100u);
    prints.push_back(sim->fingerprint());
    events.push_back(s.eventsProcessed);
  }
  for (std::size_t i = 1; i < prints.size(); ++i) {
    BOOST_CHECK_EQUAL(events[0], events[i]);
    BOOST_CHECK_EQUAL(prints[0], prints[i]);
  }
}
