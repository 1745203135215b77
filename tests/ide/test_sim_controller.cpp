// The IDE's kernel thread (ide/core, no Qt): the run it makes is vsim's run, whatever the mix of
// commands (run, pause, step, run until, restart); the selected block's facts are the dump's; bad
// input is an error, never a crash. Built under the tsan preset too: the GUI thread's side of
// every exchange is exercised here.
#define BOOST_TEST_MODULE ide_sim_controller
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "session.hpp"
#include "sim_controller.hpp"

namespace {

using namespace std::chrono_literals;

const std::string kSource = MELD_SOURCE_DIR;

vsim::Options gradientOptions() {
  vsim::Options o;
  o.world = kSource + "/examples/worlds/meld-gradient-tap.xml";
  return o;
}

struct Reference {
  std::uint64_t fingerprint, events;
  std::string dump;
};

// The same options run straight through a session, as vsim does.
Reference runHeadless(const vsim::Options& o) {
  std::ostringstream out;
  vsim::SessionStreams streams;
  streams.programOutput = &out;
  vsim::Session s(o, streams);
  s.simulation().run();
  std::ostringstream dump;
  if (s.meld()) s.meld()->dump(dump);
  return {s.simulation().fingerprint(), s.simulation().statistics().eventsProcessed, dump.str()};
}

bool over(const ide::WorldSnapshot& s) {
  return s.state == ide::RunState::Finished || s.state == ide::RunState::Failed;
}

std::shared_ptr<const ide::WorldSnapshot> waitOver(const ide::SimController& c) {
  return c.waitFor(over, 60s);
}

// The lines of one block's section of a dump.
std::vector<std::string> dumpSection(const std::string& dump, std::uint32_t block) {
  std::istringstream in(dump);
  std::vector<std::string> lines;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    const bool header = !line.empty() && std::isdigit(static_cast<unsigned char>(line[0]));
    if (header) {
      inside = line == std::to_string(block);
      continue;
    }
    if (inside) lines.push_back(line);
  }
  return lines;
}

}  // namespace

BOOST_AUTO_TEST_CASE(run_to_the_end_gives_vsims_fingerprint) {
  const Reference ref = runHeadless(gradientOptions());
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  BOOST_TEST(c.info().blockCount == 49u);
  BOOST_TEST(c.info().meld);
  BOOST_TEST(ide::runStateName(c.snapshot()->state) == std::string("paused"));
  BOOST_TEST(c.snapshot()->now == 0);
  c.run();
  const auto end = waitOver(c);
  BOOST_REQUIRE(end);
  BOOST_TEST(ide::runStateName(end->state) == std::string("finished"));
  BOOST_TEST(end->fingerprint == ref.fingerprint);
  BOOST_TEST(end->events == ref.events);
  BOOST_TEST(end->positions.size() == 49u);
}

BOOST_AUTO_TEST_CASE(steps_pauses_paced_runs_and_restarts_give_the_same_run) {
  const Reference ref = runHeadless(gradientOptions());
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  for (int i = 0; i < 5; ++i) c.step();
  BOOST_REQUIRE(c.waitFor([](const ide::WorldSnapshot& s) { return s.events == 5; }, 30s));
  // Real time for a moment (the tap comes at 1 s: this does not reach it), then pause.
  c.run(1.0);
  std::this_thread::sleep_for(50ms);
  c.pause();
  BOOST_REQUIRE(c.waitFor([](const ide::WorldSnapshot& s) { return s.state == ide::RunState::Paused; }, 30s));
  c.runUntil(simcore::kSecond / 2);
  const auto half = c.waitFor(
      [](const ide::WorldSnapshot& s) {
        return s.state == ide::RunState::Paused && s.now == simcore::kSecond / 2;
      },
      30s);
  BOOST_REQUIRE(half);
  c.run(1000.0);  // paced: 1 s of simulated time per millisecond
  const auto end = waitOver(c);
  BOOST_REQUIRE(end);
  BOOST_TEST(end->fingerprint == ref.fingerprint);

  BOOST_REQUIRE(c.restart());
  BOOST_TEST(c.snapshot()->now == 0);
  BOOST_TEST(c.snapshot()->events == 0u);
  BOOST_TEST(c.snapshot()->session > end->session);
  c.run();
  const auto again = waitOver(c);
  BOOST_REQUIRE(again);
  BOOST_TEST(again->fingerprint == ref.fingerprint);
}

BOOST_AUTO_TEST_CASE(the_selected_blocks_facts_are_its_dump_section) {
  const Reference ref = runHeadless(gradientOptions());
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  c.select(17);
  c.run();
  const auto end = waitOver(c);
  BOOST_REQUIRE(end);
  const ide::BlockDetails& d = end->selected;
  BOOST_TEST(d.id == 17u);
  BOOST_TEST(d.cell.x == 3);
  BOOST_TEST(d.cell.y == 2);
  BOOST_TEST(d.neighbors.size() == 6u);
  std::vector<std::string> shown;
  for (const ide::FactGroup& g : d.facts) shown.insert(shown.end(), g.lines.begin(), g.lines.end());
  const std::vector<std::string> expected = dumpSection(ref.dump, 17);
  BOOST_TEST(!expected.empty());
  BOOST_TEST(shown == expected, boost::test_tools::per_element());
  // Grouped by predicate: a group's lines all name it.
  for (const ide::FactGroup& g : d.facts)
    for (const std::string& l : g.lines) BOOST_TEST(l.find(g.predicate + "(") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_tap_after_the_end_runs_again) {
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  c.run();
  const auto end = waitOver(c);
  BOOST_REQUIRE(end);
  c.tap(0);
  c.run();
  const auto after = c.waitFor(
      [&](const ide::WorldSnapshot& s) {
        return s.state == ide::RunState::Finished && s.events > end->events;
      },
      30s);
  BOOST_REQUIRE(after);
  BOOST_TEST(after->colors[0] == 0xFF0000u);  // the corner is a source now: distance 0, red
}

BOOST_AUTO_TEST_CASE(bad_input_is_an_error_message) {
  ide::SimController c;
  vsim::Options o;
  o.world = kSource + "/no/such/world.xml";
  BOOST_TEST(!c.open(o));
  BOOST_TEST(!c.isOpen());
  BOOST_TEST(c.error().find("cannot open world file") != std::string::npos);
  BOOST_TEST(c.snapshot() == nullptr);
  c.run();  // commands without a run do nothing
  c.step();

  const std::string broken = std::string(MELD_BINARY_DIR) + "/ide_broken.meld";
  std::ofstream(broken) << "include #blinkyblocks.meld\n\n!neighbor(B, N, _) -o !nosuch(B).\n";
  o = gradientOptions();
  o.program = broken;
  BOOST_TEST(!c.open(o));
  BOOST_TEST(c.diagnostics().find(broken + ":3:") != std::string::npos);
  BOOST_TEST(c.error().find("has errors") != std::string::npos);

  // A good run after a bad one.
  BOOST_TEST(c.open(gradientOptions()));
}

BOOST_AUTO_TEST_CASE(the_console_gets_the_trace_with_vsims_filter) {
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  BOOST_CHECK_THROW(c.setTraceFilter("kinds=nonsense"), simcore::TraceFilterError);
  c.setTraceFilter("blocks=24;kinds=tap");
  c.run();
  BOOST_REQUIRE(waitOver(c));
  const std::vector<std::string> lines = c.takeConsoleLines();
  BOOST_REQUIRE_EQUAL(lines.size(), 1u);
  BOOST_TEST(lines[0].find("tap") != std::string::npos);
  BOOST_TEST(lines[0].find("24") != std::string::npos);
  BOOST_TEST(c.takeConsoleLines().empty());
}

BOOST_AUTO_TEST_CASE(the_selected_blocks_history_is_recorded_only_when_asked) {
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  c.select(17);
  c.run();
  auto end = waitOver(c);
  BOOST_REQUIRE(end);
  BOOST_TEST(end->selected.history.empty());  // not asked: nothing recorded

  c.setHistory(true);
  BOOST_REQUIRE(c.restart());
  c.select(17);
  c.run();
  end = waitOver(c);
  BOOST_REQUIRE(end);
  const std::vector<ide::HistoryEntry>& h = end->selected.history;
  BOOST_REQUIRE(!h.empty());
  auto has = [&](const std::string& part) {
    return std::any_of(h.begin(), h.end(),
                       [&](const ide::HistoryEntry& e) { return e.text.find(part) != e.text.npos; });
  };
  BOOST_TEST(has("+ !dist(1)"));             // its distance, from block 24 (tapped at 1 s)
  BOOST_TEST(has("+ !setColor2") == false);  // actions are not facts of the node
  BOOST_TEST(has("received a message on face"));
  BOOST_TEST(has("sent "));
  BOOST_TEST(has("event start"));
  for (std::size_t i = 1; i < h.size(); ++i) BOOST_TEST(h[i - 1].time <= h[i].time);
  const auto dist =
      std::find_if(h.begin(), h.end(), [](const ide::HistoryEntry& e) { return e.text == "+ !dist(1)"; });
  BOOST_TEST(dist->time >= simcore::kSecond);  // after the tap
}

BOOST_AUTO_TEST_CASE(why_a_fact_exists_is_vsims_tree) {
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  c.run();
  BOOST_REQUIRE(waitOver(c));
  std::uint64_t asked = c.why(10, "!dist(2)");
  auto answered = [&](const ide::WorldSnapshot& s) { return s.why && s.why->request == asked; };
  auto s = c.waitFor(answered, 30s);
  BOOST_REQUIRE(s);
  BOOST_TEST(s->why->lines.empty());
  BOOST_TEST(s->why->error.find("Record derivations") != std::string::npos);

  c.setRecordDerivations(true);
  BOOST_REQUIRE(c.restart());
  c.run();
  BOOST_REQUIRE(waitOver(c));
  asked = c.why(10, "!dist(2)");
  s = c.waitFor(answered, 30s);
  BOOST_REQUIRE(s);
  std::string tree;
  for (const meldvm::WhyLine& l : s->why->lines)
    tree += std::string(std::size_t(l.depth) * 2, ' ') + l.fact + "    " + l.how + "\n";
  // The tree `vsim --why` prints for the same fact (tests/cli/expected), the world named alike.
  std::ifstream expectedFile(kSource + "/tests/cli/expected/why-gradient.txt");
  std::string expected((std::istreambuf_iterator<char>(expectedFile)), std::istreambuf_iterator<char>());
  const std::string relative = "examples/meld/gradient-tap.meld", absolute = kSource + "/" + relative;
  for (std::size_t at = 0; (at = expected.find(relative, at)) != std::string::npos; at += absolute.size())
    expected.replace(at, relative.size(), absolute);
  BOOST_TEST(tree == expected);
  BOOST_TEST(s->why->lines[0].where == absolute + ":23");

  asked = c.why(10, "!dist(7)");
  s = c.waitFor(answered, 30s);
  BOOST_REQUIRE(s);
  BOOST_TEST(s->why->error.find("No record of !dist(7) on block 10") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(removing_a_block_while_paused_and_saving_the_world) {
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  c.runUntil(simcore::kSecond / 2);
  BOOST_REQUIRE(c.waitFor([](const ide::WorldSnapshot& s) { return s.now == simcore::kSecond / 2; }, 30s));
  c.removeBlock(17);  // between the tapped centre (24) and block 10
  BOOST_REQUIRE(c.waitFor([](const ide::WorldSnapshot& s) { return !s.alive[17]; }, 30s));
  c.run();
  const auto end = waitOver(c);
  BOOST_REQUIRE(end);
  BOOST_TEST(end->fingerprint != runHeadless(gradientOptions()).fingerprint);
  BOOST_TEST(end->error == "");
  // The gradient goes around the hole: block 10, at (3, 1) under the removed (3, 2), is 4 hops
  // from the tapped centre now (aqua) instead of 2; block 3, at (3, 0), 5 (blue) instead of 3.
  BOOST_TEST(end->colors[10] == 0x00FFFFu);
  BOOST_TEST(end->colors[3] == 0x0000FFu);
  BOOST_TEST(end->colors[16] == 0xFFFF00u);  // (2, 2): 2 hops, as before (yellow)

  const std::string saved = std::string(MELD_BINARY_DIR) + "/ide_saved_world.xml";
  std::remove(saved.c_str());
  c.saveWorld(saved);
  std::vector<std::string> console;
  for (int i = 0; i < 300 && console.empty(); ++i) {
    std::this_thread::sleep_for(10ms);
    for (std::string& l : c.takeConsoleLines())
      if (l.find("Saved the world") != std::string::npos) console.push_back(l);
  }
  BOOST_REQUIRE_EQUAL(console.size(), 1u);
  // It loads again: 48 blocks, the colours they had, the same program.
  const simcore::WorldDescription again = simcore::loadWorldXml(saved);
  BOOST_TEST(again.blocks.size() == 48u);
  vsim::Options o;
  o.world = saved;
  ide::SimController reopened;
  BOOST_REQUIRE_MESSAGE(reopened.open(o), reopened.error());
  BOOST_TEST(reopened.info().blockCount == 48u);
  BOOST_TEST(reopened.info().meld);

  c.saveWorld("/no/such/folder/w.xml");
  bool refused = false;
  for (int i = 0; i < 300 && !refused; ++i) {
    std::this_thread::sleep_for(10ms);
    for (const std::string& l : c.takeConsoleLines()) refused = refused || l.find("Cannot write") == 0;
  }
  BOOST_TEST(refused);
}

BOOST_AUTO_TEST_CASE(adding_a_block_while_paused) {
  ide::SimController c;
  BOOST_REQUIRE(c.open(gradientOptions()));
  c.runUntil(simcore::kSecond / 2);
  BOOST_REQUIRE(c.waitFor([](const ide::WorldSnapshot& s) { return s.now == simcore::kSecond / 2; }, 30s));
  auto console = [&](const std::string& part) {
    for (int i = 0; i < 300; ++i) {
      for (const std::string& l : c.takeConsoleLines())
        if (l.find(part) != std::string::npos) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  };
  c.addBlock({3, 3, 0});  // the centre: taken
  BOOST_TEST(console("Cannot add a block at (3, 3, 0)"));
  c.addBlockNextTo(48);  // the far corner: the floor is full, and one layer high
  BOOST_TEST(console("has no free cell around it"));
  c.removeBlock(48);
  c.addBlockNextTo(47);  // (5, 6): its first free neighbour cell is (6, 6), where 48 was
  BOOST_TEST(console("Added block 49 at (6, 6, 0)"));
  c.run();
  const auto end = waitOver(c);
  BOOST_REQUIRE(end);
  BOOST_TEST(end->error == "");
  BOOST_REQUIRE_EQUAL(end->positions.size(), 50u);
  BOOST_TEST(!end->alive[48]);
  BOOST_TEST(end->alive[49]);
  BOOST_TEST(end->colors[49] == 0xFF0000u);  // distance 6 from the tapped centre: red, as 48 was
}
