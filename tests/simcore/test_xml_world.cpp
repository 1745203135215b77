#define BOOST_TEST_MODULE xml_world
#include <boost/test/unit_test.hpp>
#include <sstream>
#include <string>

#include "simcore/simulation.hpp"
#include "simcore/xml_world.hpp"
#include "targets.hpp"
#include "test_support.hpp"

using simcore::Cell;
using simcore::XmlWorldError;

namespace {

const std::string kData = std::string(MELD_SOURCE_DIR) + "/tests/data/xml/";
const std::string kExamples = std::string(MELD_SOURCE_DIR) + "/examples/worlds/";

// The full message of the error that loading `file` (in tests/data/xml) throws.
std::string loadError(const std::string& file) {
  try {
    simcore::loadWorldXml(kData + file);
  } catch (const XmlWorldError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string parseError(const std::string& text) {
  try {
    simcore::parseWorldXml(text, "w.xml");
  } catch (const XmlWorldError& e) {
    return e.what();
  }
  return "(no error)";
}

// A world of one block (a world without blocks is an error) plus `body`.
const std::string kOneBlock = "<blockList><block position=\"0,0,0\"/></blockList>\n";
std::string world(const std::string& body, const std::string& attrs = "gridSize=\"4,4,4\"") {
  return "<world " + attrs + ">\n" + body + "</world>\n";
}

std::unique_ptr<simcore::Simulation> simulationFor(const simcore::WorldDescription& d) {
  const auto target = targets::makeTarget(d.target);
  BOOST_REQUIRE(target);
  simcore::SimulationConfig cfg;
  cfg.seed = d.seed.value_or(1);
  auto sim = std::make_unique<simcore::Simulation>(*target, d.grid, cfg);
  simcore::populateSimulation(d, *sim);
  return sim;
}

}  // namespace

// --- Examples and the format ---

BOOST_AUTO_TEST_CASE(examples_load_without_warnings) {
  for (const char* name :
       {"blinky-box.xml", "blinky-tower.xml", "smartblocks-line.xml", "smartblocks-flood.xml"}) {
    BOOST_TEST_CONTEXT(name) {
      const simcore::WorldDescription d = simcore::loadWorldXml(kExamples + name);
      BOOST_TEST(d.warnings.empty());
      BOOST_TEST(targets::makeTarget(d.target).has_value());
      BOOST_TEST(!d.blocks.empty());
    }
  }
}

BOOST_AUTO_TEST_CASE(blinky_box_is_a_4x4x3_box) {
  const simcore::WorldDescription d = simcore::loadWorldXml(kExamples + "blinky-box.xml");
  BOOST_TEST(d.target == "blinkyblocks");
  BOOST_TEST((d.grid.x == 6 && d.grid.y == 6 && d.grid.z == 5));
  BOOST_TEST(d.seed.value_or(0) == 7u);
  BOOST_TEST(d.blocks.size() == 48u);
  // x fastest, then y, then z.
  BOOST_TEST((d.blocks[0].cell == Cell{1, 1, 0}));
  BOOST_TEST((d.blocks[1].cell == Cell{2, 1, 0}));
  BOOST_TEST((d.blocks[4].cell == Cell{1, 2, 0}));
  BOOST_TEST((d.blocks[47].cell == Cell{4, 4, 2}));
  BOOST_TEST(d.blocks[0].color.value() == 0xFF0000u);
  BOOST_TEST(d.blocks[20].color.value() == 0x00FF00u);
  BOOST_TEST(d.blocks[40].color.value() == 0x0000FFu);
  BOOST_TEST(d.listColor.value() == 0x808080u);
  BOOST_TEST(d.blockSize == "40,40,40");
  BOOST_TEST(d.camera.present);
  BOOST_TEST(d.camera.attributes.size() == 3u);
  BOOST_TEST(d.spotlight.present);
  BOOST_REQUIRE(d.taps.size() == 1u);
  BOOST_TEST(d.taps[0].block == 47u);
  BOOST_TEST(d.taps[0].time == simcore::kSecond);
  BOOST_REQUIRE(d.accels.size() == 1u);
  BOOST_TEST(d.accels[0].value[2] == -1000);
  BOOST_TEST(d.accels[0].time == 2500 * simcore::kMillisecond);
}

BOOST_AUTO_TEST_CASE(smartblocks_line_and_list_color) {
  const simcore::WorldDescription d = simcore::loadWorldXml(kExamples + "smartblocks-line.xml");
  BOOST_TEST(d.target == "smartblocks");
  BOOST_REQUIRE(d.blocks.size() == 10u);
  BOOST_TEST(d.blocks[0].color.value() == 0xFFFF00u);
  BOOST_TEST(d.blocks[1].color.value() == 0x4080FFu);  // the list's color
  BOOST_TEST((d.blocks[9].cell == Cell{14, 5, 0}));
}

BOOST_AUTO_TEST_CASE(line_directions_and_planar_forms) {
  const auto d = simcore::parseWorldXml(
      world("<blockList><blocksLine origin=\"3,0\" direction=\"-x\" length=\"3\"/>"
            "<blocksLine origin=\"0,1,0\" direction=\"+y\" length=\"2\"/></blockList>\n",
            "gridSize=\"4,4\""),
      "w.xml");
  BOOST_TEST(d.grid.z == 1);
  BOOST_REQUIRE(d.blocks.size() == 5u);
  BOOST_TEST((d.blocks[0].cell == Cell{3, 0, 0}));
  BOOST_TEST((d.blocks[2].cell == Cell{1, 0, 0}));
  BOOST_TEST((d.blocks[4].cell == Cell{0, 2, 0}));
  BOOST_TEST(!d.blocks[0].color.has_value());  // no color anywhere: the target's default
}

BOOST_AUTO_TEST_CASE(relative_code_and_program_paths_follow_the_file) {
  const auto d = simcore::parseWorldXml(
      world(kOneBlock, "gridSize=\"2,2,2\" code=\"lib/c.so\" program=\"../p.meld\""), "worlds/sub/w.xml");
  BOOST_TEST(d.code == "worlds/sub/lib/c.so");
  BOOST_TEST(d.program == "worlds/p.meld");
  const auto abs = simcore::parseWorldXml(world(kOneBlock, "gridSize=\"2,2,2\" code=\"/opt/c.so\""), "worlds/w.xml");
  BOOST_TEST(abs.code == "/opt/c.so");
}

BOOST_AUTO_TEST_CASE(unknown_target_names_are_kept_not_judged) {
  const auto d = simcore::loadWorldXml(kData + "unknown-things.xml");
  BOOST_TEST(d.target == "catoms9d");
  BOOST_TEST(!targets::makeTarget(d.target).has_value());
}

BOOST_AUTO_TEST_CASE(unknown_elements_and_attributes_are_warnings) {
  const auto d = simcore::loadWorldXml(kData + "unknown-things.xml");
  const std::string f = kData + "unknown-things.xml";
  BOOST_REQUIRE(d.warnings.size() == 3u);
  BOOST_TEST(d.warnings[0] == f + ":2:43: warning: unknown attribute 'colour' of <world> ignored");
  BOOST_TEST(d.warnings[1] == f + ":4:29: warning: unknown attribute 'master' of <block> ignored");
  BOOST_TEST(d.warnings[2] == f + ":6:3: warning: unknown element <obstacles> ignored");
  BOOST_TEST(d.blocks.size() == 1u);
}

BOOST_AUTO_TEST_CASE(stray_text_is_a_warning) {
  const auto d = simcore::parseWorldXml(world("  hello\n" + kOneBlock), "w.xml");
  BOOST_REQUIRE(d.warnings.size() == 1u);
  BOOST_TEST(d.warnings[0] == "w.xml:2:3: warning: text inside <world> ignored");
}

BOOST_AUTO_TEST_CASE(columns_count_characters_and_crlf_is_fine) {
  // "é" is two bytes; the column is in characters.
  BOOST_TEST(
      parseError(
          "<!-- é -->\r\n<world gridSize=\"4,4,4\">\r\n<blockList><!-- é --><block position=\"9,0,0\"/>"
          "</blockList></world>") ==
      "w.xml:3:29: error: attribute 'position' of <block>: \"9,0,0\" is outside the grid 4x4x4");
}

// --- Errors: one test per class ---

BOOST_AUTO_TEST_CASE(error_missing_file) {
  BOOST_TEST(loadError("no-such-file.xml") ==
             kData + "no-such-file.xml: error: cannot open the world file: No such file or directory");
  BOOST_TEST(loadError("") == kData + ": error: is a directory, not a world file");
}

BOOST_AUTO_TEST_CASE(error_malformed_xml) {
  BOOST_TEST(loadError("malformed.xml") ==
             kData + "malformed.xml:5:5: error: malformed XML: Start-end tags mismatch");
  BOOST_TEST(parseError("<world gridSize=\"1,1,1\"") ==
             "w.xml:1:18: error: malformed XML: Error parsing element attribute");
}

BOOST_AUTO_TEST_CASE(error_missing_world_root) {
  BOOST_TEST(loadError("no-world-root.xml") ==
             kData + "no-world-root.xml:2:1: error: the root element is <universe>, expected <world> or <vs>");
  BOOST_TEST(parseError("") == "w.xml:1:1: error: no root element: expected <world>");
  BOOST_TEST(parseError("<!-- nothing -->\n") == "w.xml:1:1: error: no root element: expected <world>");
}

BOOST_AUTO_TEST_CASE(error_bad_grid_size) {
  BOOST_TEST(loadError("bad-gridsize.xml") == kData +
                                                  "bad-gridsize.xml:2:8: error: attribute 'gridSize' of "
                                                  "<world>: \"4,0,4\" is not three positive integers");
  BOOST_TEST(parseError("<world/>") == "w.xml:1:1: error: <world> needs attribute 'gridSize'");
  BOOST_TEST(parseError(world(kOneBlock, "gridSize=\"a,b,c\"")) ==
             "w.xml:1:8: error: attribute 'gridSize' of <world>: \"a,b,c\" is not three positive integers");
  BOOST_TEST(parseError(world(kOneBlock, "gridSize=\"1,2,3,4\"")) ==
             "w.xml:1:8: error: attribute 'gridSize' of <world>: \"1,2,3,4\" is not three positive integers");
  BOOST_TEST(parseError(world(kOneBlock, "gridSize=\"65536,65536,2\"")) ==
             "w.xml:1:8: error: attribute 'gridSize' of <world>: \"65536,65536,2\" has more than 2^31 cells");
  BOOST_TEST(
      parseError(world(kOneBlock, "gridSize=\"4294967296,1,1\"")) ==
      "w.xml:1:8: error: attribute 'gridSize' of <world>: \"4294967296,1,1\" is not three positive integers");
  // Exactly 2^31 cells is allowed.
  BOOST_TEST(simcore::parseWorldXml(world(kOneBlock, "gridSize=\"65536,32768,1\""), "w.xml").grid.y == 32768);
}

BOOST_AUTO_TEST_CASE(error_bad_numbers) {
  BOOST_TEST(
      loadError("bad-position.xml") ==
      kData +
          "bad-position.xml:5:12: error: attribute 'position' of <block>: \"1,x,3\" is not three integers");
  BOOST_TEST(loadError("bad-color.xml") == kData +
                                               "bad-color.xml:4:29: error: attribute 'color' of <block>: "
                                               "\"255,256,0\" is not a color: r,g,b in 0..255, #RRGGBB or 0xRRGGBB");
  BOOST_TEST(
      parseError(world("<blockList color=\"1,2\"/>\n")) ==
      "w.xml:2:12: error: attribute 'color' of <blockList>: \"1,2\" is not a color: r,g,b in 0..255, #RRGGBB or 0xRRGGBB");
  BOOST_TEST(
      parseError(world("<blockList blockSize=\"40,-1,40\"/>\n")) ==
      "w.xml:2:12: error: attribute 'blockSize' of <blockList>: \"40,-1,40\" is not three positive numbers");
  BOOST_TEST(parseError(world(kOneBlock, "gridSize=\"4,4,4\" seed=\"-3\"")) ==
             "w.xml:1:25: error: attribute 'seed' of <world>: \"-3\" is not a non-negative integer");
  BOOST_TEST(
      parseError(
          world("<blockList><blocksLine origin=\"0,0,0\" direction=\"w\" length=\"2\"/></blockList>\n")) ==
      "w.xml:2:39: error: attribute 'direction' of <blocksLine>: \"w\" is not one of x, y, z, -x, -y, -z");
  BOOST_TEST(parseError(world(
                 "<blockList><blocksLine origin=\"0,0,0\" direction=\"x\" length=\"0\"/></blockList>\n")) ==
             "w.xml:2:53: error: attribute 'length' of <blocksLine>: \"0\" is not a positive integer");
  BOOST_TEST(parseError(world("<schedule><accel block=\"0\" time=\"1s\" value=\"1,2\"/></schedule>\n")) ==
             "w.xml:2:38: error: attribute 'value' of <accel>: \"1,2\" is not three integers");
  BOOST_TEST(parseError(world("<blockList><block/></blockList>\n")) ==
             "w.xml:2:12: error: <block> needs attribute 'position'");
}

BOOST_AUTO_TEST_CASE(error_position_outside_the_grid) {
  BOOST_TEST(loadError("outside-grid.xml") == kData +
                                                  "outside-grid.xml:4:12: error: attribute 'position' of "
                                                  "<block>: \"0,0,4\" is outside the grid 4x4x4");
  BOOST_TEST(parseError(world("<blockList><blocksBox origin=\"2,2,2\" size=\"3,1,1\"/></blockList>\n")) ==
             "w.xml:2:38: error: attribute 'size' of <blocksBox>: \"3,1,1\" makes the box from (2,2,2) leave "
             "the grid");
  BOOST_TEST(parseError(world(
                 "<blockList><blocksLine origin=\"1,0,0\" direction=\"-x\" length=\"3\"/></blockList>\n")) ==
             "w.xml:2:54: error: attribute 'length' of <blocksLine>: \"3\" makes the line from (1,0,0) leave "
             "the grid");
}

BOOST_AUTO_TEST_CASE(error_two_blocks_in_one_cell) {
  BOOST_TEST(loadError("same-cell.xml") ==
             kData + "same-cell.xml:5:12: error: <block>: cell (1,1,1) already holds block 7 (line 4)");
}

BOOST_AUTO_TEST_CASE(error_bad_time) {
  BOOST_TEST(loadError("bad-time.xml") == kData +
                                              "bad-time.xml:7:20: error: attribute 'time' of <tap>: \"soon\" "
                                              "is not a duration (like 1.5s, 250ms, 10us, 42ns)");
  BOOST_TEST(parseError(world("<schedule><tap block=\"0\" time=\"-1s\"/></schedule>\n")) ==
             "w.xml:2:26: error: attribute 'time' of <tap>: \"-1s\" is not a duration (like 1.5s, 250ms, "
             "10us, 42ns)");
}

BOOST_AUTO_TEST_CASE(error_tap_on_unknown_block) {
  // The schedule comes before the blocks in this file: ids are checked once all blocks are known.
  BOOST_TEST(
      loadError("tap-unknown-block.xml") ==
      kData + "tap-unknown-block.xml:5:10: error: block 2 does not exist: the world has 2 blocks (ids 0..1)");
  BOOST_TEST(
      parseError(world("<schedule><tap block=\"x\" time=\"1s\"/></schedule>\n")) ==
      "w.xml:2:16: error: attribute 'block' of <tap>: \"x\" is not a block id (a non-negative integer)");
}

// --- Building a simulation ---

BOOST_AUTO_TEST_CASE(populate_adds_blocks_and_schedule) {
  const auto d = simcore::loadWorldXml(kExamples + "blinky-tower.xml");
  auto sim = simulationFor(d);
  testsupport::Script script(*sim);
  BOOST_REQUIRE(sim->world().blockCount() == 5u);
  BOOST_TEST(sim->world().block(0).color == 0x0080FFu);
  BOOST_TEST(sim->world().block(4).color == 0xFFFFFFu);
  BOOST_TEST((sim->world().block(3).cell == Cell{1, 1, 3}));
  sim->runUntilEmpty();
  const auto taps = script.of(4, VS_EV_TAP);
  BOOST_REQUIRE(taps.size() == 2u);
  BOOST_TEST(taps[0].time == 500 * simcore::kMillisecond);
  BOOST_TEST(taps[1].time == 1500 * simcore::kMillisecond);
  const auto sensor = script.of(4, VS_EV_SENSOR);
  BOOST_REQUIRE(sensor.size() == 1u);
  BOOST_TEST(sensor[0].values[0] == 200);
  BOOST_TEST(sensor[0].values[2] == -980);
}

BOOST_AUTO_TEST_CASE(populate_uses_the_target_default_color) {
  const auto d = simcore::parseWorldXml(
      world("<blockList><block position=\"0,0\"/></blockList>\n", "gridSize=\"2,2\" target=\"sb\""), "w.xml");
  auto sim = simulationFor(d);
  BOOST_TEST(sim->world().block(0).color == sim->target().defaultColor);
}

BOOST_AUTO_TEST_CASE(populate_errors_point_at_the_element) {
  auto d = simcore::loadWorldXml(kExamples + "blinky-tower.xml");
  d.taps[1].block = 9;  // edited by code after loading
  const auto target = targets::makeTarget("blinkyblocks");
  simcore::Simulation sim(*target, d.grid);
  try {
    simcore::populateSimulation(d, sim);
    BOOST_FAIL("no error");
  } catch (const XmlWorldError& e) {
    BOOST_TEST(e.what() == kExamples + "blinky-tower.xml:15:5: error: block 9 does not exist");
    BOOST_TEST(e.line() == 15);
  }
  // A tap on a target without a tap sensor.
  auto tapped =
      simcore::parseWorldXml(world("<blockList><block position=\"0,0,0\"/></blockList>\n<schedule><tap "
                                   "block=\"0\" time=\"1s\"/></schedule>\n",
                                   "gridSize=\"2,2,1\" target=\"smartblocks\""),
                             "w.xml");
  BOOST_CHECK_EXCEPTION(simulationFor(tapped), XmlWorldError, [](const XmlWorldError& e) {
    return std::string(e.what()) == "w.xml:3:11: error: target 'smartblocks' has no tap sensor";
  });
  // A simulation whose grid is smaller than the file's.
  const auto big =
      simcore::parseWorldXml(world("<blockList><block position=\"3,3,3\"/></blockList>\n"), "w.xml");
  simcore::Simulation small(*target, simcore::GridSize{2, 2, 2});
  BOOST_CHECK_EXCEPTION(simcore::populateSimulation(big, small), XmlWorldError, [](const XmlWorldError& e) {
    return std::string(e.what()) == "w.xml:2:12: error: cell (3,3,3) is outside the simulation's grid";
  });
}

// --- Exporting ---

BOOST_AUTO_TEST_CASE(export_round_trip_after_changes) {
  const auto d = simcore::loadWorldXml(kExamples + "blinky-box.xml");
  auto sim = simulationFor(d);
  sim->removeBlock(5);
  sim->world().block(7).color = 0x123456;
  std::ostringstream out;
  simcore::exportWorldXml(*sim, d, out);
  const auto back = simcore::parseWorldXml(out.str(), "exported.xml");
  BOOST_TEST(back.warnings.empty());
  BOOST_TEST(back.target == "blinkyblocks");
  BOOST_TEST((back.grid.x == 6 && back.grid.y == 6 && back.grid.z == 5));
  BOOST_TEST(back.seed.value_or(0) == 7u);
  BOOST_TEST(back.listColor.value() == 0x808080u);
  BOOST_TEST(back.blockSize == "40,40,40");
  BOOST_TEST(back.camera.attributes == d.camera.attributes);
  BOOST_TEST(back.spotlight.attributes == d.spotlight.attributes);
  BOOST_TEST(back.taps.empty());
  BOOST_REQUIRE(back.blocks.size() == 47u);
  std::size_t i = 0;
  for (simcore::BlockId id = 0; id < sim->world().blockCount(); ++id) {
    const simcore::Block& b = sim->world().block(id);
    if (!sim->world().isAlive(id)) continue;
    BOOST_TEST((back.blocks[i].cell == b.cell));
    BOOST_TEST(back.blocks[i].color.value() == b.color);
    ++i;
  }
  BOOST_TEST(back.blocks[6].color.value() == 0x123456u);  // old id 7, renumbered after the removal
}

BOOST_AUTO_TEST_CASE(export_writes_the_final_configuration_of_a_run) {
  // Smart Blocks that wander and flood: cells and colors change during the run.
  const auto d =
      simcore::parseWorldXml(world("<blockList><blocksBox origin=\"6,6,0\" size=\"4,4,1\"/></blockList>\n",
                                   "gridSize=\"16,16,1\" target=\"smartblocks\" seed=\"3\""),
                             "walk.xml");
  auto sim = simulationFor(d);
  sim->setBlockCode(&testsupport::kRandomWalk);
  sim->runUntilEmpty();
  std::ostringstream first;
  simcore::exportWorldXml(*sim, d, first);
  const auto back = simcore::parseWorldXml(first.str(), "exported.xml");
  BOOST_REQUIRE(back.blocks.size() == 16u);
  bool moved = false;
  for (std::size_t i = 0; i < back.blocks.size(); ++i) {
    BOOST_TEST((back.blocks[i].cell == sim->world().block(simcore::BlockId(i)).cell));
    BOOST_TEST(back.blocks[i].color.value() == sim->world().block(simcore::BlockId(i)).color);
    moved = moved || !(back.blocks[i].cell == d.blocks[i].cell);
  }
  BOOST_TEST(moved);
  // Exporting the reloaded world gives the same blocks again.
  auto again = simulationFor(back);
  std::ostringstream second;
  simcore::exportWorldXml(*again, back, second);
  const auto twice = simcore::parseWorldXml(second.str(), "exported.xml");
  BOOST_REQUIRE(twice.blocks.size() == back.blocks.size());
  for (std::size_t i = 0; i < back.blocks.size(); ++i)
    BOOST_TEST((twice.blocks[i].cell == back.blocks[i].cell));
}

BOOST_AUTO_TEST_CASE(export_makes_code_paths_absolute) {
  // A path with a folder is taken relative to the world file (a bare name is the front end's to
  // search for: vsim's code_search.hpp); the export writes it absolute.
  const auto d = simcore::parseWorldXml(R"(<world gridSize="3,3,1" target="smartblocks" code="../lib/brownian_flood.so">
<blockList><block position="0,0,0"/></blockList></world>)",
                                        "/work/worlds/w.xml");
  BOOST_TEST(d.code == "/work/lib/brownian_flood.so");
  BOOST_TEST(d.codeAsWritten == "../lib/brownian_flood.so");
  const auto target = targets::makeTarget(d.target);
  simcore::Simulation sim(*target, d.grid);
  simcore::populateSimulation(d, sim);
  std::ostringstream out;
  simcore::exportWorldXml(sim, d, out);
  const auto back = simcore::parseWorldXml(out.str(), "/elsewhere/exported.xml");
  BOOST_TEST(back.code == "/work/lib/brownian_flood.so");
}

// ---- VisibleSim's own forms (issue 10, point 12) ----

BOOST_AUTO_TEST_CASE(visiblesim_vs_root_and_its_other_sections) {
  const auto d = simcore::parseWorldXml(
      "<?xml version=\"1.0\"?>\n<vs>\n<visuals><window size=\"800,600\"/></visuals>\n<vm serverport=\"7800\"/>\n"
      "<parameters/>\n<world gridSize=\"3,3,1\">\n" + kOneBlock + "</world>\n</vs>\n",
      "w.xml");
  BOOST_TEST(d.blocks.size() == 1u);
  BOOST_TEST(d.warnings.empty());
  BOOST_TEST(parseError("<vs><visuals/></vs>") == "w.xml:1:1: error: <vs> holds no <world>");
}

BOOST_AUTO_TEST_CASE(visiblesim_bitmap_rows_in_planes) {
  const auto d = simcore::parseWorldXml(
      world("<blockList><blocksLine line=\"0\" values=\"0110\"/>"
            "<blocksLine line=\"2\" plane=\"1\" values=\"1001\"/></blockList>\n",
            "gridSize=\"4,3,2\""),
      "w.xml");
  BOOST_REQUIRE(d.blocks.size() == 4u);
  BOOST_TEST((d.blocks[0].cell == Cell{1, 0, 0}));
  BOOST_TEST((d.blocks[1].cell == Cell{2, 0, 0}));
  BOOST_TEST((d.blocks[2].cell == Cell{0, 2, 1}));
  BOOST_TEST((d.blocks[3].cell == Cell{3, 2, 1}));
  BOOST_TEST(parseError(world("<blockList><blocksLine line=\"0\" values=\"01x\"/></blockList>\n")) ==
             "w.xml:2:33: error: attribute 'values' of <blocksLine>: \"01x\" holds 'x': only 0 and 1 are allowed");
  BOOST_TEST(parseError(world("<blockList><blocksLine line=\"0\" values=\"000001\"/></blockList>\n")) ==
             "w.xml:2:33: error: attribute 'values' of <blocksLine>: \"000001\" has a block at x = 5, outside the grid");
  BOOST_TEST(parseError(world("<blockList><blocksLine line=\"7\" values=\"1\"/></blockList>\n")) ==
             "w.xml:2:24: error: attribute 'line' of <blocksLine>: \"7\" is not a row of the grid (0..3)");
}

BOOST_AUTO_TEST_CASE(visiblesim_block_box) {
  const auto d = simcore::parseWorldXml(
      world("<blockList><blockBox boxOrigin=\"1,1,0\" boxSize=\"2,2,1\"/></blockList>\n"), "w.xml");
  BOOST_REQUIRE(d.blocks.size() == 4u);
  BOOST_TEST((d.blocks[3].cell == Cell{2, 2, 0}));
  // Without a size the box reaches the far corner of the grid.
  const auto all = simcore::parseWorldXml(world("<blockList><blockBox/></blockList>\n", "gridSize=\"2,3,2\""), "w.xml");
  BOOST_TEST(all.blocks.size() == 12u);
}

BOOST_AUTO_TEST_CASE(colors_in_every_visiblesim_spelling) {
  const auto d = simcore::parseWorldXml(
      world("<blockList><block position=\"0,0,0\" color=\"#FF8000\"/><block position=\"1,0,0\" color=\"0x0080ff\"/>"
            "<block position=\"2,0,0\" color=\"127.6,0.2,255.0\"/><block position=\"3,0,0\" color=\"1,2,3,255\"/>"
            "</blockList>\n"),
      "w.xml");
  BOOST_TEST(d.blocks[0].color.value() == 0xFF8000u);
  BOOST_TEST(d.blocks[1].color.value() == 0x0080FFu);
  BOOST_TEST(d.blocks[2].color.value() == 0x8000FFu);
  BOOST_TEST(d.blocks[3].color.value() == 0x010203u);
  BOOST_TEST(parseError(world("<blockList><block position=\"0,0,0\" color=\"#12345\"/></blockList>\n")) ==
             "w.xml:2:36: error: attribute 'color' of <block>: \"#12345\" is not a color: r,g,b in 0..255, "
             "#RRGGBB or 0xRRGGBB");
}

BOOST_AUTO_TEST_CASE(the_visiblesim_paper_figure_7_file) {
  // Lower-case gridsize, two-component grid and positions: the planar form.
  const auto d = simcore::parseWorldXml(
      "<world gridsize=\"20,20\">\n<blocklist blocksize=\"25,25,11\">\n<block position=\"5,5\"/>\n"
      "<block position=\"6,5\" color=\"0,255,0\"/>\n</blocklist>\n</world>\n",
      "w.xml");
  BOOST_TEST(d.grid.x == 20);
  BOOST_TEST(d.grid.z == 1);
  BOOST_REQUIRE(d.blocks.size() == 2u);
  BOOST_TEST((d.blocks[1].cell == Cell{6, 5, 0}));
  BOOST_TEST(d.warnings.empty());
}

BOOST_AUTO_TEST_CASE(a_world_without_blocks_is_an_error) {
  BOOST_TEST(parseError(world("<blockList/>\n")) ==
             "w.xml:1:1: error: the world has no block (no <block>, <blocksBox>, <blockBox>, <blocksLine> or "
             "<csg> in a <blockList>)");
  // A <csg> solid's blocks depend on the lattice: the loader only checks its text.
  BOOST_TEST(parseError(world("<blockList><csg content=\"cube([4,4,4])\"/></blockList>\n")) ==
             "w.xml:2:39: error: <csg content>: expected ';' at the end of the text");
}

BOOST_AUTO_TEST_CASE(catoms_orientation_is_kept_on_export) {
  const auto d = simcore::parseWorldXml(
      world("<blockList><block position=\"1,1,1\" orientation=\"3\"/><block position=\"2,1,1\"/></blockList>\n",
            "gridSize=\"4,4,4\" target=\"catoms3d\""),
      "w.xml");
  BOOST_REQUIRE(d.blocks[0].kept.size() == 1u);
  BOOST_TEST(d.warnings.empty());
  auto sim = simulationFor(d);
  std::ostringstream out;
  simcore::exportWorldXml(*sim, d, out);
  const auto back = simcore::parseWorldXml(out.str(), "w2.xml");
  BOOST_REQUIRE(back.blocks[0].kept.size() == 1u);
  BOOST_TEST(back.blocks[0].kept[0].second == "3");
  BOOST_TEST(back.blocks[1].kept.empty());
}
