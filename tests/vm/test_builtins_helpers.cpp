#define BOOST_TEST_MODULE vm_builtins_helpers
#include <boost/test/unit_test.hpp>
#include <set>

#include "builtins_fixture.hpp"

using namespace bitest;

namespace {

struct Threads : SchedulerView {
  std::int32_t threads = 4;
  double priority(NodeId) const override { return 0; }
  ThreadId owner(NodeId) const override { return 0; }
  std::int32_t staticNodes(ThreadId) const override { return 0; }
  bool isStatic(NodeId) const override { return false; }
  std::int32_t queueSize(NodeId) const override { return 0; }
  std::int32_t factsProved() const override { return 0; }
  std::int32_t factsConsumed() const override { return 0; }
  std::int32_t threadCount() const override { return threads; }
};

}  // namespace

BOOST_FIXTURE_TEST_SUITE(helpers, Fix)

BOOST_AUTO_TEST_CASE(minimax_score_on_lists) {
  // Row 0 is player 1's: +200 when 1 is the root player, -100 otherwise, whoever moves.
  const Value won = ints({1, 1, 1, 0, 2, 2, 0, 0, 0});
  BOOST_CHECK_EQUAL(call("minimax_score", {won, I(1), I(1)}, tInt).asInt(), 200);
  BOOST_CHECK_EQUAL(call("minimax_score", {won, I(2), I(1)}, tInt).asInt(), 200);
  BOOST_CHECK_EQUAL(call("minimax_score", {won, I(1), I(2)}, tInt).asInt(), -100);
  // No line: 0, except on an empty board, which counts the root player's cells.
  const Value open = ints({2, 0, 1, 0, 2, 1, 0, 0, 0});
  BOOST_CHECK_EQUAL(call("minimax_score", {open, I(1), I(1)}, tInt).asInt(), 0);
  const Value empty = ints({0, 0, 0, 0, 0, 0, 0, 0, 0});
  BOOST_CHECK_EQUAL(call("minimax_score", {empty, I(1), I(0)}, tInt).asInt(), 9);
  BOOST_CHECK_EQUAL(call("minimax_score", {empty, I(1), I(1)}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("minimax_points", {open, I(2)}, tInt).asInt(), 2);
  BOOST_CHECK_THROW(call("minimax_score", {ints({1, 1}), I(1), I(1)}, tInt), RuntimeError);
}

BOOST_AUTO_TEST_CASE(minimax_score2_on_arrays) {
  // Column 1 is player 2's with 6 cells played: 6 * 200 for root 2, 6 * -100 for root 1.
  const Value a = tuple(tAI, {I(0), I(2), I(1), I(1), I(2), I(1), I(0), I(2), I(0)});
  BOOST_CHECK_EQUAL(call("minimax_score2", {a, I(1), I(2)}, tInt).asInt(), 1200);
  BOOST_CHECK_EQUAL(call("minimax_score2", {a, I(1), I(1)}, tInt).asInt(), -600);
  // A full board without a line counts the root player's cells.
  const Value full = tuple(tAI, {I(1), I(2), I(1), I(2), I(1), I(2), I(2), I(1), I(2)});
  BOOST_CHECK_EQUAL(call("minimax_score2", {full, I(1), I(2)}, tInt).asInt(), 5);
  BOOST_CHECK_EQUAL(call("minimax_points2", {full, I(1)}, tInt).asInt(), 4);
}

BOOST_AUTO_TEST_CASE(bit_vectors) {
  BOOST_CHECK_EQUAL(show("demergemessages", {ints({1, 4, 0}), ints({2, 4, 8, 16})}, tLI), "[3,4,8]");
  BOOST_CHECK_THROW(call("demergemessages", {ints({1, 2}), ints({1})}, tLI), RuntimeError);
  Rng rng = Rng::forThread(0);
  ctx.rng = &rng;
  // Each item is one bit among the low bits - 1 bits; the draws follow the stream.
  std::set<std::int32_t> seen;
  for (Value l = call("degeneratevector", {I(200), I(5)}, tLI); !l.isNil(); l = listTail(l)) {
    const std::int32_t v = listHead(l).asInt();
    BOOST_CHECK(v == 1 || v == 2 || v == 4 || v == 8);
    seen.insert(v);
  }
  BOOST_CHECK_EQUAL(seen.size(), 4u);
  BOOST_CHECK_THROW(call("degeneratevector", {I(1), I(1)}, tLI), RuntimeError);
}

BOOST_AUTO_TEST_CASE(partitions_map_cells_to_threads) {
  Threads s;
  ctx.sched = &s;
  // A 4x4 grid on 4 threads: four cells each, the last thread takes what is left.
  BOOST_CHECK_EQUAL(show("partition_vertical", {I(3), I(0), I(4), I(4)}, tThread), "#T0");
  BOOST_CHECK_EQUAL(show("partition_vertical", {I(0), I(1), I(4), I(4)}, tThread), "#T1");
  BOOST_CHECK_EQUAL(show("partition_horizontal", {I(1), I(0), I(4), I(4)}, tThread), "#T1");
  BOOST_CHECK_EQUAL(show("partition_horizontal", {I(3), I(3), I(4), I(4)}, tThread), "#T3");
  // Grid: 2x2 blocks of 2x2 cells in snake order: block (1, 1) is the third.
  BOOST_CHECK_EQUAL(show("partition_grid", {I(0), I(0), I(4), I(4)}, tThread), "#T0");
  BOOST_CHECK_EQUAL(show("partition_grid", {I(3), I(3), I(4), I(4)}, tThread), "#T2");
  s.threads = 1;
  BOOST_CHECK_EQUAL(show("partition_grid", {I(3), I(3), I(4), I(4)}, tThread), "#T0");
}

BOOST_AUTO_TEST_SUITE_END()
