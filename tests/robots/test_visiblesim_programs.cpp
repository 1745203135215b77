// Forms of VisibleSim's Blinky Blocks Meld programs that must run unchanged (issue 10, point 12):
// a delay on an action, sensed events declared persistent, a program that declares the sensing
// predicates itself and still includes the target's file; the robot check is one function, made
// by `meldc --robots` and by the runtime alike.
#define BOOST_TEST_MODULE robots_visiblesim_programs
#include <boost/test/unit_test.hpp>

#include "meldvm/block_runtime.hpp"
#include "robot_fixture.hpp"

using robots::World;

BOOST_AUTO_TEST_CASE(an_action_with_a_delay_runs_after_it) {
  World w("blinkyblocks", robots::line(2), R"(
include #blinkyblocks.meld
!setColor2(X, 0).
!vacant(X, left) -o setColor2(X, 3)@+1s.
)");
  const std::uint32_t red = 0xFF0000, green = 0x00FF00;
  w.sim->runUntil(simcore::SimTime(999) * 1000000);
  BOOST_TEST(w.color(0) == red);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.color(0) == green);  // block 0 has no left neighbour
  BOOST_TEST(w.color(1) == red);
  BOOST_TEST(w.sim->now() >= simcore::SimTime(1000) * 1000000);
}

BOOST_AUTO_TEST_CASE(a_persistent_tap_is_sensed_too) {
  World w("blinkyblocks", robots::line(2), R"(
type tap(node).
type tapped(node).
!tap(X) -o !tapped(X).
)");
  w.sim->scheduleTap(1, simcore::SimTime(1) * 1000000000);
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(1) == "!tap()\n!tapped()\n");
  BOOST_TEST(w.facts(0) == "");
}

BOOST_AUTO_TEST_CASE(own_declarations_of_the_sensing_predicates_and_the_target_file) {
  // Identical to the declarations of blinkyblocks.meld (common.meld): accepted.
  World w("blinkyblocks", robots::line(3), R"(
include #blinkyblocks.meld
type route neighbor(node, node, int).
type vacant(node, int).
type ends(node).
!vacant(X, left) -o !ends(X).
!vacant(X, right) -o !ends(X).
)");
  w.sim->runUntilEmpty();
  BOOST_TEST(w.vm->error() == "");
  BOOST_TEST(w.facts(0).find("!ends()") != std::string::npos);
  BOOST_TEST(w.facts(1).find("!ends()") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(one_robot_check_for_the_compiler_and_the_runtime) {
  const auto wrong = robots::compile("type linear tap(node, int).\n");
  BOOST_CHECK_EXCEPTION(meldvm::checkRobotProgram(*wrong), meldvm::BlockProgramError, [](const auto& e) {
    return std::string(e.what()).find("predicate 'tap' must be declared as `type linear tap(node).`") !=
           std::string::npos;
  });
  BOOST_CHECK_THROW(meldvm::BlockRuntime(*wrong, 2), meldvm::BlockProgramError);
  const auto persistent = robots::compile("type tap(node).\n");
  BOOST_CHECK_NO_THROW(meldvm::checkRobotProgram(*persistent));
}

BOOST_AUTO_TEST_CASE(randint_draws_from_the_block_stream) {
  // Issue 10, point 16: the seed of the run changes the draws; the other blocks do not.
  const char* program = R"(
type linear roll(node, int).
roll(X, randint(1000000)).
)";
  auto rolls = [&](int blocks, std::uint64_t seed) {
    World w("blinkyblocks", robots::line(blocks), program, {}, {20, 20, 20}, seed);
    w.sim->runUntilEmpty();
    BOOST_TEST(w.vm->error() == "");
    return w.facts(0) + "|" + w.facts(1);
  };
  BOOST_TEST(rolls(2, 1) == rolls(2, 1));
  BOOST_TEST(rolls(2, 1) != rolls(2, 2));
  BOOST_TEST(rolls(2, 7) == rolls(5, 7));  // blocks 0 and 1 draw the same beside three more
}
