// The Meld VM behind the block ABI (issue 4): sensing facts, messages between blocks, retraction
// when the world changes, message sizes, the non-neighbour error, reproducible runs.
#define BOOST_TEST_MODULE robots_block_runtime
#include <boost/test/unit_test.hpp>

#include "robot_fixture.hpp"

using robots::World;

namespace {

const char* kGradient = R"(
type route neighbor(node, node, int).
type linear tap(node).
type hops(node, min int).
tap(X) -o !hops(X, 0).
!hops(X, D), !neighbor(X, Y, _) -o !hops(Y, D + 1).
!hops(X, D) -o !setColor2(X, D).
)";

}  // namespace

BOOST_AUTO_TEST_CASE(sensing_facts_describe_the_neighbourhood_at_start) {
  World w("blinkyblocks", robots::line(3), R"(
type route neighbor(node, node, int).
type vacant(node, int).
type neighborCount(node, int).
type at(node, int, int, int).
)");
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  // Blinky Blocks faces: right 2 (+x), left 4 (-x).
  BOOST_TEST(w.facts(1) ==
             "!at(1, 0, 0)\n!neighbor(@0, 4)\n!neighbor(@2, 2)\n!neighborCount(2)\n"
             "!vacant(0)\n!vacant(1)\n!vacant(3)\n!vacant(5)\n");
  BOOST_TEST(w.facts(0).find("!neighborCount(1)") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_gradient_from_a_tapped_block_reaches_every_block_with_its_hop_distance) {
  World w("blinkyblocks", robots::line(5), kGradient);
  w.sim->scheduleTap(1, simcore::SimTime(1) * 1000000000);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  const int expected[5] = {1, 0, 1, 2, 3};
  for (std::uint32_t b = 0; b < 5; ++b) {
    BOOST_TEST(w.facts(b).find("!hops(" + std::to_string(expected[b]) + ")") != std::string::npos);
    // setColor2 with the VisibleSim palette: 0 red, 1 orange, 2 yellow, 3 green.
    const std::uint32_t palette[4] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00};
    BOOST_TEST(w.color(b) == palette[expected[b]]);
  }
}

BOOST_AUTO_TEST_CASE(removing_a_block_retracts_its_neighbor_facts_at_the_others) {
  World w("blinkyblocks", robots::line(3), R"(
type route neighbor(node, node, int).
type vacant(node, int).
type neighborCount(node, int).
)");
  w.sim->runUntil(simcore::SimTime(1) * 1000000000);
  BOOST_TEST(w.facts(1).find("!neighbor(@2, 2)") != std::string::npos);
  w.sim->removeBlock(2);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  const std::string f = w.facts(1);
  BOOST_TEST(f.find("!neighbor(@2, 2)") == std::string::npos);
  BOOST_TEST(f.find("!vacant(2)") != std::string::npos);
  BOOST_TEST(f.find("!neighborCount(1)") != std::string::npos);
  BOOST_TEST(f.find("!neighborCount(2)") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_removed_blocks_inverse_route_facts_are_taken_back_by_its_neighbours) {
  // A rule that reaches a neighbour's facts (localized over the inverse route ___robhgien, which
  // the neighbour sends): when block 1 leaves, blocks 0 and 2 hold inverse facts naming it that
  // block 1 cannot take back over the broken links. They drop them themselves, so the flood that
  // follows neither sends a fact to the departed block (a run-time error before) nor keeps it.
  const char* reach = R"(
type route neighbor(node, node, int).
type linear tap(node).
type hops(node, min int).
tap(X) -o !hops(X, 0).
!neighbor(X, Y, _), !hops(Y, D) -o !hops(X, D + 1).
)";
  World w("blinkyblocks", robots::line(3), reach);
  w.sim->runUntil(simcore::kSecond);
  BOOST_TEST(w.facts(0).find("!___robhgien(@1, 4)") != std::string::npos);
  w.sim->removeBlock(1);
  w.sim->scheduleTap(0, 2 * simcore::kSecond);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(0).find("___robhgien") == std::string::npos);
  BOOST_TEST(w.facts(2).find("___robhgien") == std::string::npos);
  BOOST_TEST(w.facts(0).find("!hops(0)") != std::string::npos);
  BOOST_TEST(w.facts(2).find("!hops(") == std::string::npos);  // cut off from the tapped block
}

BOOST_AUTO_TEST_CASE(a_fact_for_a_neighbour_is_a_message_of_its_encoded_size) {
  // ping(node, int): predicate id (2 bytes) + flags (1) + int (4) = 7 bytes on the link.
  World w("blinkyblocks", robots::line(2), R"(
type route neighbor(node, node, int).
type linear ping(node, int).
type linear got(node, int).
!neighbor(X, Y, _) -o ping(Y, 42).
ping(X, N) -o got(X, N).
)");
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.vm->messages() == 2u);
  BOOST_TEST(w.vm->messageBytes() == 14u);
  BOOST_TEST(w.sim->statistics().bytesSent == 14u);
  BOOST_TEST(w.facts(0) == "got(42)\n!neighbor(@1, 2)\n");
}

BOOST_AUTO_TEST_CASE(a_fact_for_a_block_that_is_not_a_neighbour_is_an_error_naming_the_rule) {
  World w("blinkyblocks", robots::line(4), R"(
type linear hello(node).
hello(@0).
hello(X) -o hello(@3).
)");
  w.sim->runUntilEmpty();
  const std::string e = w.vm->error();
  BOOST_TEST(e.find("not a neighbour") != std::string::npos, e);
  BOOST_TEST(e.find("@3") != std::string::npos, e);
  BOOST_TEST(e.find("rule 1") != std::string::npos, e);
  BOOST_TEST(e.find("hello(X) -o hello(@3).") != std::string::npos, e);
}

BOOST_AUTO_TEST_CASE(repeated_runs_give_the_same_fingerprint_and_facts) {
  std::uint64_t fp[2];
  std::string dump[2];
  for (int i = 0; i < 2; ++i) {
    std::vector<simcore::Cell> cells;
    for (int x = 0; x < 4; ++x)
      for (int y = 0; y < 3; ++y) cells.push_back({x, y, 0});
    World w("blinkyblocks", cells, kGradient);
    w.sim->scheduleTap(5, 1000000);
    w.sim->runUntilEmpty();
    fp[i] = w.sim->fingerprint();
    dump[i] = w.dump();
  }
  BOOST_TEST(fp[0] == fp[1]);
  BOOST_TEST(dump[0] == dump[1]);
}

BOOST_AUTO_TEST_CASE(computing_time_delays_the_messages_a_node_run_sends) {
  // With 1 ms per rule the neighbour hears later than with the default 1 us.
  simcore::SimTime arrival[2];
  for (int i = 0; i < 2; ++i) {
    meldvm::BlockRuntimeOptions o;
    o.timePerRuleNs = i == 0 ? 1000 : 1000000;
    World w("blinkyblocks", robots::line(2), kGradient, o);
    w.sim->scheduleTap(0, 0);
    w.sim->runUntilEmpty();
    arrival[i] = w.sim->now();
  }
  BOOST_TEST(arrival[1] > arrival[0] + 900000);
}

BOOST_AUTO_TEST_CASE(move_to_retracts_and_reasserts_the_position_and_the_links) {
  // Smart Blocks: block 0 at (0,0) moves to (0,1) once; `at` follows, and its link to block 1 at
  // (1,0) breaks (faces: north 0 (+y), east 1, south 2, west 3).
  World w("smartblocks", {{0, 0, 0}, {1, 0, 0}}, R"(
type route neighbor(node, node, int).
type vacant(node, int).
type at(node, int, int, int).
type linear action moveTo(node, int, int, int).
type linear go(node).
type linear start(node).
start(@0).
start(X) -o go(X)@+100ms.
go(X), !at(X, A, B, C) -o moveTo(X, A, B + 1, C).
)");
  w.sim->runUntil(simcore::SimTime(50) * 1000000);  // before the move: linked
  BOOST_TEST(w.facts(1).find("!neighbor(@0, 3)") != std::string::npos);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(0) == "!at(0, 1, 0)\n!vacant(0)\n!vacant(1)\n!vacant(2)\n!vacant(3)\n");
  BOOST_TEST(w.facts(1).find("!neighbor(@0, 3)") == std::string::npos);
  BOOST_TEST(w.facts(1).find("!vacant(3)") != std::string::npos);
  BOOST_TEST((w.sim->world().block(0).cell == simcore::Cell{0, 1, 0}));
}

BOOST_AUTO_TEST_CASE(move_to_from_a_persistent_rule_retracts_the_old_position) {
  // The rule runs while `at` is being delivered to the block: the retraction that moveTo posts to
  // the block itself must not be lost with the mailbox being delivered (each old `at` stayed).
  World w("smartblocks", {{0, 0, 0}}, R"(
type at(node, int, int, int).
type linear action moveTo(node, int, int, int).
!at(B, X, Y, Z), Y < 2 -o moveTo(B, X, Y + 1, Z).
)");
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(0) == "!at(0, 2, 0)\n");
  BOOST_TEST(w.sim->statistics().motionsEnded == 2u);
}

BOOST_AUTO_TEST_CASE(move_to_rotates_a_catom_3d_over_its_neighbour) {
  // Catoms 3D: block 0 at (2,2,2) rotates over block 1 at (3,2,2) (its side0) into (2,2,3) (its
  // top2); it then touches block 1 through connector bottom9, and block 1 it through top3.
  World w("catoms3d", {{2, 2, 2}, {3, 2, 2}}, R"(
type route neighbor(node, node, int).
type at(node, int, int, int).
type linear action moveTo(node, int, int, int).
type linear go(node).
type linear start(node).
start(@0).
start(X) -o go(X)@+100ms.
go(X), !at(X, A, B, C) -o moveTo(X, A, B, C + 1).
)");
  w.sim->runUntil(simcore::SimTime(50) * 1000000);
  BOOST_TEST(w.facts(0) == "!at(2, 2, 2)\n!neighbor(@1, 0)\n");
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(0) == "!at(2, 2, 3)\n!neighbor(@1, 9)\n");
  BOOST_TEST(w.facts(1).find("!neighbor(@0, 3)") != std::string::npos);
  BOOST_TEST((w.sim->world().block(0).cell == simcore::Cell{2, 2, 3}));
}

BOOST_AUTO_TEST_CASE(air_jets_and_mobile_sensing_need_physics) {
  // A Smart Blocks world without mobiles: senseMobile answers nothing, airJet is a run-time error
  // naming the action (examples/meld/conveyor.meld runs them on a world with physics: cli.conveyor).
  World w("smartblocks", {{0, 0, 0}}, R"(
type linear action senseMobile(node).
type linear mobileAt(node, int, float, float, int).
type linear action airJet(node, int, float, int).
type linear start(node).
start(@0).
start(X) -o senseMobile(X), airJet(X, 1, 0.5, 10).
)");
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error().find("airJet(1, 0.500000, 10): refused by the world (no physics here)") !=
             std::string::npos, w.vm->error());
  BOOST_TEST(w.facts(0).find("mobileAt") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_delayed_fact_arrives_after_its_delay_in_simulated_time) {
  // ping(X)@+250ms for the block itself waits on a timer; pong for the neighbour leaves 250 ms
  // late on the link.
  World w("blinkyblocks", robots::line(2), R"(
type route neighbor(node, node, int).
type linear start(node).
type linear ping(node).
type linear pong(node).
start(@0).
start(X) -o ping(X)@+250ms.
ping(X), !neighbor(X, Y, _) -o pong(Y)@+250ms.
)");
  w.sim->runUntil(simcore::SimTime(240) * 1000000);
  BOOST_TEST(w.facts(0).find("ping()") == std::string::npos);
  w.sim->runUntil(simcore::SimTime(260) * 1000000);
  BOOST_TEST(w.facts(0).find("ping()") == std::string::npos);  // consumed at once by the next rule
  BOOST_TEST(w.facts(1).find("pong()") == std::string::npos);  // still on its way
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(1).find("pong()") != std::string::npos);
  BOOST_TEST(w.sim->now() > simcore::SimTime(500) * 1000000);
  BOOST_TEST(w.sim->now() < simcore::SimTime(510) * 1000000);
}

BOOST_AUTO_TEST_CASE(catoms_2d_and_3d_run_the_gradient_over_their_lattices) {
  // Catoms 2D: a hexagonal row (faces right 0 / left 3); Catoms 3D: a row along x (side0 / side6).
  for (const char* target : {"catoms2d", "catoms3d"}) {
    World w(target, robots::line(4), kGradient);
    w.sim->scheduleTap(0, 1000000);
    w.sim->runUntilEmpty();
    BOOST_TEST(w.vm->error() == "", target);
    for (std::uint32_t b = 0; b < 4; ++b)
      BOOST_TEST(w.facts(b).find("!hops(" + std::to_string(b) + ")") != std::string::npos,
                 target << " " << b);
  }
}

BOOST_AUTO_TEST_CASE(a_block_added_to_the_running_world_gets_a_node_and_joins_the_gradient) {
  // Blocks 0..2 on a line; after the gradient from block 0 settled, a block joins at x = 3 next
  // to block 2: its node starts with its neighbour, takes hops 3 and colours itself, and block 2
  // sees a new neighbour.
  World w("blinkyblocks", robots::line(3), kGradient);
  w.sim->scheduleTap(0, simcore::kSecond);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.sim->addBlockWhileRunning({1, 0, 0}, 0x808080) == simcore::kNoBlock);  // taken
  const simcore::BlockId added = w.sim->addBlockWhileRunning({3, 0, 0}, 0x808080);
  BOOST_REQUIRE_EQUAL(added, 3u);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(3).find("!hops(3)") != std::string::npos, w.facts(3));
  BOOST_TEST(w.facts(3).find("!neighbor(@2, 4)") != std::string::npos);
  BOOST_TEST(w.facts(2).find("!neighbor(@3, 2)") != std::string::npos);
  BOOST_TEST(w.color(3) != 0x808080u);
  // The same again: the run is deterministic.
  World again("blinkyblocks", robots::line(3), kGradient);
  again.sim->scheduleTap(0, simcore::kSecond);
  again.sim->runUntilEmpty();
  again.sim->addBlockWhileRunning({3, 0, 0}, 0x808080);
  again.sim->runUntilEmpty();
  BOOST_TEST(again.sim->fingerprint() == w.sim->fingerprint());
  BOOST_TEST(again.dump() == w.dump());
}
