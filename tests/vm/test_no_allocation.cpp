// The store's hot paths allocate nothing per fact in the steady state: after a warm-up, deriving
// and consuming linear facts (with string and list arguments), counting and retracting persistent
// facts, aggregate inputs with retraction and index look-ups perform no heap allocation. Counted by
// replacing the global operator new in this test.
#define BOOST_TEST_MODULE vm_no_allocation
#include <atomic>
#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <new>

#include "../common/counting_new.hpp"
#include "vm_fixture.hpp"

using namespace vmtest;

namespace {

struct Workload {
  Store s;
  TypeId listInt = s.types.list(TypeTable::kInt);
  TypeId listFloat = s.types.list(TypeTable::kFloat);
  PredId msg = s.linear("msg", {TypeTable::kNode, TypeTable::kString, listInt});
  PredId edge = s.persistent("edge", {TypeTable::kNode, TypeTable::kInt});
  PredId dist = s.aggregate("dist", {TypeTable::kInt, TypeTable::kNode}, AggregateKind::Min, 0);
  PredId vec = s.aggregate("vec", {listFloat}, AggregateKind::Sum, 0);
  std::uint32_t index = 0;
  std::uint64_t checksum = 0;

  Workload() {
    s.open(64);
    index = s.db->requestIndex(msg, 0);
  }

  // One round of churn; the same work every round, so a warm-up reaches the working sizes.
  void round(int r) {
    Database& db = *s.db;
    Heap& heap = s.heap;
    for (NodeId n = 0; n < 64; ++n) {
      for (int i = 0; i < 20; ++i) {
        const Value str = heap.makeString("payload");
        const Value items[3] = {I(i), I(r), I(int(n))};
        const Value list = heap.makeList(listInt, items);
        const Value args[3] = {N((n + NodeId(i)) % 8), str, list};
        db.addLinear(n, msg, args);
        heap.release(TypeTable::kString, str);
        heap.release(listInt, list);
      }
      for (FactRef f = db.firstWithKey(n, msg, index, N(3)); f != kNoFact; f = db.nextWithKey(msg, index, f))
        checksum += db.args(msg, f)[2].isNil() ? 0 : 1;
      for (FactRef f = db.first(n, msg); f != kNoFact;) {
        const FactRef next = db.next(msg, f);
        db.consume(n, msg, f);
        f = next;
      }
      for (int i = 0; i < 10; ++i) {
        const Value e[2] = {N(NodeId(i)), I(i % 3)};
        db.derive(n, edge, e);
        db.derive(n, edge, e);
        const Value d[2] = {I(100 - i), N(NodeId(i))};
        checksum += db.derive(n, dist, d).added ? 1 : 0;
      }
      const Value floats[2] = {F(0.5), F(r)};
      const Value fl = heap.makeList(listFloat, floats);
      db.derive(n, vec, &fl);
      db.retract(n, vec, &fl);
      heap.release(listFloat, fl);
      for (int i = 0; i < 10; ++i) {
        const Value e[2] = {N(NodeId(i)), I(i % 3)};
        db.retract(n, edge, e, 2);
        const Value d[2] = {I(100 - i), N(NodeId(i))};
        checksum += db.retract(n, dist, d).removed ? 1 : 0;
      }
    }
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(steady_state_store_allocates_nothing) {
  Workload w;
  for (int r = 0; r < 5; ++r) w.round(r);  // warm-up: pools, free lists and hash tables grow here
  const std::size_t live = w.s.heap.liveObjects();
  const std::uint64_t before = testcommon::allocations();
  for (int r = 0; r < 50; ++r) w.round(r);
  const std::uint64_t during = testcommon::allocations() - before;
  BOOST_TEST_MESSAGE("allocations during 50 rounds: " << during << ", checksum " << w.checksum);
  BOOST_TEST(during == 0u);
  BOOST_TEST(w.checksum > 0u);
  BOOST_TEST(w.s.heap.liveObjects() == live);  // nothing leaked either
  for (NodeId n = 0; n < 64; ++n) {
    BOOST_TEST(w.s.db->factCount(n, w.msg) == 0u);
    BOOST_TEST(w.s.db->factCount(n, w.edge) == 0u);
    BOOST_TEST(w.s.db->factCount(n, w.dist) == 0u);
  }
}

// The counter works: a fresh database does allocate.
BOOST_AUTO_TEST_CASE(the_counter_sees_allocations) {
  const std::uint64_t before = testcommon::allocations();
  Workload w;
  w.round(0);
  BOOST_TEST(testcommon::allocations() > before);
}
