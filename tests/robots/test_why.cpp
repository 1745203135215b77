// Why a fact exists (vm/engine derivation_log): fact specs in the forms users type, the trees of a
// program on blocks (a message from a neighbour, the sensed facts, axioms at their lines), and
// recording changing nothing of the run.
#define BOOST_TEST_MODULE robots_why
#include <sstream>

#include "meldvm/derivation_log.hpp"
#include "robot_fixture.hpp"

using namespace robots;

namespace {

// Three blocks in a line; block 0 starts a hop count, line 5 is the rule that passes it on.
const char* kHops = R"(include #blinkyblocks.meld
type hops(node, min int).
type name(node, string).
!hops(@0, 0).
!name(@2, "far, away").
!neighbor(B, N, _), !hops(N, D) -o !hops(B, D + 1).
)";

std::string why(const meldvm::DerivationLog& log, const meldvm::FactAt& f) {
  std::ostringstream out;
  BOOST_REQUIRE(meldvm::printWhy(out, log, f));
  return out.str();
}

}  // namespace

BOOST_AUTO_TEST_CASE(fact_specs_in_every_form) {
  World w("blinkyblocks", line(3), kHops);
  const meldvm::Program& p = *w.program;
  for (const char* spec : {"hops(@2, 2)", "!hops(@2,2)", "hops(2)@2", " HOPS ( @2 , 2 ) "}) {
    const meldvm::FactAt f = meldvm::parseFactSpec(spec, p);
    BOOST_TEST(f.node == 2u);
    BOOST_TEST(f.text == "!hops(2)", spec);
  }
  BOOST_TEST(meldvm::parseFactSpec("name(@2, \"far, away\")", p).text == "!name(\"far, away\")");
  BOOST_TEST(meldvm::parseFactSpec("tap()@1", p).text == "tap()");
  BOOST_TEST(meldvm::parseFactSpec("tap(@1)", p).text == "tap()");
  for (const char* bad : {"hops", "hops(2, 2)", "nosuch(@1)", "hops(@x, 1)", "(@1)"})
    BOOST_CHECK_THROW(meldvm::parseFactSpec(bad, p), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(tree_of_a_fact_from_a_neighbour) {
  World w("blinkyblocks", line(3), kHops);
  meldvm::DerivationLog log;
  w.vm->recordDerivations(&log);
  w.sim->run();
  BOOST_REQUIRE(w.vm->error().empty());
  const std::string tree = why(log, meldvm::parseFactSpec("hops(@2, 2)", *w.program));
  std::istringstream lines(tree);
  std::string first;
  std::getline(lines, first);
  // hops(2) at block 2 was derived at block 1 (the rule reaches the neighbour's hops) and sent.
  BOOST_TEST(first.find("!hops(@2, 2)    rule ") == 0u, first);
  BOOST_TEST(first.find("prog.meld:6 at @1, sent to @2 as a message") != std::string::npos, first);
  BOOST_TEST(tree.find("    !hops(@0, 0)    axiom ") != std::string::npos, tree);
  BOOST_TEST(tree.find("prog.meld:4") != std::string::npos, tree);
  BOOST_TEST(tree.find("!neighbor(@2, @1, 4)    sensed by the block at 0.000000 s") != std::string::npos,
             tree);
  BOOST_TEST(tree.find("!neighbor(@1, @0, 4)    sensed by the block") != std::string::npos, tree);
  // The axiom with a string that holds a comma and a blank.
  BOOST_TEST(why(log, meldvm::parseFactSpec("name(@2, \"far, away\")", *w.program)).find("axiom ") !=
             std::string::npos);
  BOOST_TEST(!meldvm::printWhy(std::cout, log, meldvm::parseFactSpec("hops(@2, 7)", *w.program)));
  BOOST_TEST(log.size() > 0u);
  BOOST_TEST(log.bytesInUse() > log.size() * sizeof(meldvm::Derivation));
}

BOOST_AUTO_TEST_CASE(recording_changes_nothing_of_the_run) {
  World plain("blinkyblocks", line(6), kHops), recorded("blinkyblocks", line(6), kHops);
  meldvm::DerivationLog log;
  recorded.vm->recordDerivations(&log);
  plain.sim->run();
  recorded.sim->run();
  BOOST_TEST(plain.dump() == recorded.dump());
  BOOST_TEST(plain.sim->fingerprint() == recorded.sim->fingerprint());
  BOOST_TEST(plain.vm->machine().derivations() == nullptr);
}
