// How a shard's node run takes in its mailbox (Machine::deliverIncoming): at most 16 chunks of it
// per run, the earliest arrivals first, the rest in the node's next run (the serial VM takes in
// the whole box); and with a safe point for the runtime every 256 facts stored, not only between
// rules, so that a rebalance does not wait for thousands of facts. At such a safe point the running
// node does not move, and facts the runtime hands it meanwhile wait until the delivery is over.
#define BOOST_TEST_MODULE vm_shard_delivery
#include <atomic>
#include <boost/test/unit_test.hpp>

#include "shard_fixture.hpp"

using namespace bctest;

namespace {

// Three nodes; no rule reads `a(node, int)`: a node run that takes in `a` facts only stores them,
// so its only safe points are the delivery's.
struct ThreeNodes {
  PredId a = 0;
  std::unique_ptr<Program> program =
      initOnlyProgram(3, [this](Program& p) { a = pred(p, "a", {TypeTable::kInt}, true); });
};

// A shard of a threaded run, or (asShard false) the serial VM.
struct Shard {
  ThreeNodes program;
  TestShardLink link;
  std::atomic<bool> rebalanceWanted{true};
  MailSlabs mailSlabs{2};
  std::unique_ptr<Machine> machine;
  explicit Shard(bool asShard = true) {
    MachineOptions o;
    if (asShard) {
      o.shard = &link;
      o.placement = {0, 2, 0, 3};
      o.mailSlabs = &mailSlabs;
      o.safePointFlag = &rebalanceWanted;
    }
    machine = std::make_unique<Machine>(*program.program, std::move(o));
    while (machine->runNext()) {
    }
    link.safePoints = 0;
  }
  void send(NodeId n, std::int64_t i) {
    const Value v = Value::fromInt(i);
    machine->receive(n, program.a, &v, false);
  }
};

}  // namespace

// `a(node, int)` is narrow: a message takes one word, 15 of them to the box's first chunk (128
// bytes), 31 to each next one (256 bytes).
constexpr int kFactsPerChunk = 31, kChunksPerRun = 16;

BOOST_AUTO_TEST_CASE(a_shard_node_takes_in_sixteen_chunks_per_run_and_runs_again_for_the_rest) {
  Shard s;
  s.rebalanceWanted = false;
  for (int i = 0; i < 1000; ++i) s.send(0, i);  // 33 chunks
  const std::uint64_t before = s.machine->stats().nodeRuns;
  BOOST_REQUIRE(s.machine->runNext());
  BOOST_TEST(s.machine->stats().nodeRuns - before == 3u);  // 16 chunks, 16, then the last one
  BOOST_TEST(s.machine->database().factCount(0, s.program.a) == 1000u);
  BOOST_TEST(!s.machine->runNext());
}

BOOST_AUTO_TEST_CASE(the_serial_vm_takes_in_the_whole_mailbox_in_one_run) {
  Shard s(false);
  for (int i = 0; i < 1000; ++i) s.send(0, i);
  const std::uint64_t before = s.machine->stats().nodeRuns;
  BOOST_REQUIRE(s.machine->runNext());
  BOOST_TEST(s.machine->stats().nodeRuns - before == 1u);
  BOOST_TEST(s.machine->database().factCount(0, s.program.a) == 1000u);
}

BOOST_AUTO_TEST_CASE(a_node_taking_in_hundreds_of_facts_reaches_a_safe_point_every_256) {
  Shard s;
  // 496: one safe point each run (the first run takes 480, the second 496, the last 16)
  const int perRun = kFactsPerChunk * kChunksPerRun;
  for (int i = 0; i < 2 * perRun; ++i) s.send(0, i);
  BOOST_REQUIRE(s.machine->runNext());
  BOOST_TEST(s.link.safePoints == 2);
  BOOST_TEST(s.machine->database().factCount(0, s.program.a) == std::uint32_t(2 * perRun));
}

BOOST_AUTO_TEST_CASE(without_a_rebalance_wanted_the_delivery_only_looks_at_the_flag) {
  Shard s;
  s.rebalanceWanted = false;
  for (int i = 0; i < 1000; ++i) s.send(0, i);
  BOOST_REQUIRE(s.machine->runNext());
  BOOST_TEST(s.link.safePoints == 0);
  BOOST_TEST(s.machine->database().factCount(0, s.program.a) == 1000u);
}

BOOST_AUTO_TEST_CASE(at_a_delivery_safe_point_the_running_node_stays_and_its_new_facts_wait) {
  Shard s;
  for (int i = 0; i < 300; ++i) s.send(0, i);
  s.send(1, 7);  // node 1 waits behind node 0: it may be given away
  bool movable = true;
  std::vector<NodeId> given;
  s.link.atSafePoint = [&] {
    movable = s.machine->movableNow(0);
    given = s.machine->pickNodesToGive(5, true);
    s.send(0, 1000);  // for the node whose box is being read: stored after the delivery
  };
  BOOST_REQUIRE(s.machine->runNext());
  BOOST_TEST(s.link.safePoints == 1);
  BOOST_TEST(!movable);
  BOOST_TEST(given == (std::vector<NodeId>{1, 2}), boost::test_tools::per_element());
  BOOST_TEST(s.machine->database().factCount(0, s.program.a) == 301u);
  BOOST_TEST(!s.machine->runNext());  // node 1 was handed out of the queue, node 0 is done
}
