// Which nodes a shard gives away when another thread steals work (Machine::pickNodesToGive): a
// band at the end of its ids that faces the taker, holding the asked number of queued nodes and
// the idle nodes between them (up to two per queued node), never nodes whose facts are not in the
// shard or static ones.
#define BOOST_TEST_MODULE vm_work_stealing
#include <boost/test/unit_test.hpp>

#include "shard_fixture.hpp"

using namespace bctest;

namespace {

// Thread 0 of two, owning nodes 0..10, that has run `runs` nodes; the 12 nodes each start with
// `_init` (queued), which one rule consumes. They start in the scheduler's heap, which serves them
// 0, 10, 9, 8, ... (§6.11's start-up order): after 4 runs, 1..7 wait. The owner table says every
// node is thread 0's: node 11 started on thread 1, which has just handed it over (set-cpu) in the
// rebalance under way, and its facts have not arrived yet, so thread 0 must not give it away.
struct Shard {
  std::unique_ptr<Program> program = initOnlyProgram(12);
  TestShardLink link;
  MailSlabs mailSlabs{2};
  std::unique_ptr<Machine> machine;
  explicit Shard(int runs = 4) {
    MachineOptions o;
    o.shard = &link;
    o.placement = {0, 2, 0, 11};
    o.mailSlabs = &mailSlabs;
    machine = std::make_unique<Machine>(*program, std::move(o));
    for (int i = 0; i < runs; ++i) BOOST_REQUIRE(machine->runNext());
    BOOST_REQUIRE_EQUAL(machine->waitingNodes(), std::size_t(11 - runs));
  }
};

using Nodes = std::vector<NodeId>;

}  // namespace

BOOST_AUTO_TEST_CASE(a_taker_above_gets_the_band_of_the_highest_ids_with_the_idle_nodes_in_it) {
  Shard s;
  // 6 and 7 are the two highest queued; 8, 9 and 10 (idle) lie beyond; 11 is not here yet.
  BOOST_TEST(s.machine->pickNodesToGive(2, true) == (Nodes{6, 7, 8, 9, 10}),
             boost::test_tools::per_element());
  BOOST_TEST(s.machine->waitingNodes() == 5u);  // 1..5 stay queued
}

BOOST_AUTO_TEST_CASE(a_taker_below_gets_the_band_of_the_lowest_ids) {
  Shard s;
  BOOST_TEST(s.machine->pickNodesToGive(2, false) == (Nodes{0, 1, 2}), boost::test_tools::per_element());
  BOOST_TEST(s.machine->waitingNodes() == 5u);  // 3..7
}

BOOST_AUTO_TEST_CASE(idle_nodes_beyond_two_per_queued_node_stay_but_the_queued_ones_still_go) {
  Shard s(6);  // 1..5 wait; 6..10 are idle
  BOOST_TEST(s.machine->pickNodesToGive(1, true) == (Nodes{5, 9, 10}), boost::test_tools::per_element());
  Shard t;
  t.machine->coordinateOwned(Opcode::SET_STATIC, 9, 0);  // pinned (§5.7): never given
  BOOST_TEST(t.machine->pickNodesToGive(1, true) == (Nodes{7, 8, 10}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(more_than_the_queue_holds_gives_the_whole_queue_and_the_band_ends_at_its_last_node) {
  Shard s;
  BOOST_TEST(s.machine->pickNodesToGive(100, true) == (Nodes{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}),
             boost::test_tools::per_element());
  BOOST_TEST(s.machine->waitingNodes() == 0u);
  BOOST_TEST(s.machine->pickNodesToGive(3, true).empty());
}
