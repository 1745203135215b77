// How a shard's node run takes in its mailbox (Machine::deliverIncoming): at most 16 chunks of it
// per run, the earliest arrivals first, the rest in the node's next run (the serial VM takes in
// the whole box); and with a safe point for the runtime every 256 facts stored, not only between
// rules, so that a rebalance does not wait for thousands of facts. At such a safe point the running
// node does not move, and facts the runtime hands it meanwhile wait until the delivery is over.
// And which linear facts a run sends skip the mailbox (Machine::storeSentLinear): those for a node
// of the shard's own with an empty mailbox and a short list of the predicate.
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

// A Machine running program P: a shard of a threaded run (thread 0 of 2, owning the three nodes
// unless owners says otherwise), or (asShard false) the serial VM; with safePoints, the shard
// looks at rebalanceWanted.
template <class P>
struct MachineFor {
  P program;
  TestShardLink link;
  std::atomic<bool> rebalanceWanted{true};
  MailSlabs mailSlabs{2};
  std::unique_ptr<Machine> machine;
  MachineFor(bool asShard, bool safePoints, std::vector<ThreadId> owners = {}) {
    link.owners = std::move(owners);
    MachineOptions o;
    if (asShard) {
      o.shard = &link;
      o.placement = {0, 2, 0, 3};
      o.mailSlabs = &mailSlabs;
      if (safePoints) o.safePointFlag = &rebalanceWanted;
    }
    machine = std::make_unique<Machine>(*program.program, std::move(o));
  }
};

// ThreeNodes run until quiescent (their `_init` consumed), the safe points counted from then on.
struct Shard : MachineFor<ThreeNodes> {
  explicit Shard(bool asShard = true) : MachineFor(asShard, true) {
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

namespace {

// Three nodes; rule 0 consumes `_init` and sends a(@1, 0), ..., a(@1, 39) (all three nodes run
// it). No rule reads `a`.
constexpr std::uint32_t kSent = 40;
struct SendingProgram {
  PredId a = 0;
  std::unique_ptr<Program> program = [this] {
    auto p = std::make_unique<Program>();
    p->initPredicate = pred(*p, "_init", {}, true);
    a = pred(*p, "a", {TypeTable::kInt}, true);
    emit(p->globalsInit, Opcode::RET);
    for (std::uint32_t n = 0; n < 3; ++n) {
      p->nodeSourceIds.push_back(n);
      p->nodeAxioms.push_back(Program::kNoAxioms);
    }
    Rule r;
    r.block.slots = 1;
    r.block.registerTypes = {TypeTable::kNode, TypeTable::kInt};
    r.bodyPredicates = {p->initPredicate};
    loop(r.block, Opcode::ITER, {p->initPredicate, 0, kLinConsume | kIterConsumableClass}, [&] {
      emit(r.block, Opcode::MOVN, {0, 1});
      for (std::uint32_t i = 0; i < kSent; ++i) {
        emit(r.block, Opcode::MOVI, {1, i});
        emit(r.block, Opcode::SEND, {a, 0, 1, 1});
      }
      emit(r.block, Opcode::FIRE, {0});
    });
    emit(r.block, Opcode::RET);
    p->rules.push_back(std::move(r));
    verifyProgram(*p);
    return p;
  }();
};

struct SendingShard : MachineFor<SendingProgram> {
  explicit SendingShard(bool asShard, std::vector<ThreadId> owners = {})
      : MachineFor(asShard, false, std::move(owners)) {}
  std::vector<std::int64_t> factsOfNode1() const {
    const Database& db = machine->database();
    std::vector<std::int64_t> values;
    for (FactRef f = db.first(1, program.a); f != kNoFact; f = db.next(program.a, f))
      values.push_back(db.args(program.a, f)[0].asInt());
    return values;
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(a_shard_stores_what_a_run_sends_its_own_node_at_once_up_to_32_facts) {
  SendingShard s(true);
  BOOST_REQUIRE(s.machine->runNext());  // node 0 runs and sends node 1 forty facts
  // The first 32 delivered are in node 1's list already, the other 8 in its mailbox.
  BOOST_TEST(s.machine->database().factCount(1, s.program.a) == 32u);
  BOOST_TEST(s.machine->hasWork(1));
  while (s.machine->runNext()) {
  }
  // Node 1 took in the 8, then sent itself 40 (to its mailbox: its list was long), as did node 2.
  // The serial VM stores all of them on arrival: the same list, in the same order (the
  // established VM's delivery order, send_order.hpp: one run's facts for one node and predicate
  // in reverse sending order).
  SendingShard serial(false);
  BOOST_REQUIRE(serial.machine->runNext());
  BOOST_TEST(serial.machine->database().factCount(1, serial.program.a) == kSent);
  while (serial.machine->runNext()) {
  }
  std::vector<std::int64_t> expected;
  for (int from = 0; from < 3; ++from)
    for (std::uint32_t i = kSent; i-- > 0;) expected.push_back(i);
  BOOST_TEST(serial.factsOfNode1() == expected, boost::test_tools::per_element());
  BOOST_TEST(s.factsOfNode1() == expected, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(a_fact_for_a_node_with_mail_waiting_goes_behind_the_mail) {
  SendingShard s(true);
  const Value early = Value::fromInt(-1);
  s.machine->receive(1, s.program.a, &early, false);  // from another thread: in node 1's mailbox
  BOOST_REQUIRE(s.machine->runNext());                // node 0's forty follow it there
  BOOST_TEST(s.machine->database().factCount(1, s.program.a) == 0u);
  while (s.machine->runNext()) {
  }
  const std::vector<std::int64_t> facts = s.factsOfNode1();  // in arrival order
  BOOST_REQUIRE(facts.size() == 3 * kSent + 1);
  BOOST_TEST(facts[0] == -1);
  for (std::uint32_t i = 0; i < kSent; ++i) BOOST_TEST(facts[1 + i] == std::int64_t(kSent - 1 - i));
}

BOOST_AUTO_TEST_CASE(facts_for_another_threads_node_go_to_that_thread) {
  SendingShard s(true, {0, 1, 0});
  BOOST_REQUIRE(s.machine->runNext());
  BOOST_TEST(s.link.remoteSends == int(kSent));
  BOOST_TEST(s.machine->database().factCount(1, s.program.a) == 0u);
}
