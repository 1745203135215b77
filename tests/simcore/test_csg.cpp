// VisibleSim's CSG solids (simcore/csg.hpp) and the <csg> element of world files: the language,
// VisibleSim's geometry (inclusive boundaries, its bounding boxes), and the blocks a world gets on
// each lattice.
#define BOOST_TEST_MODULE simcore_csg
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <string>

#include "simcore/csg.hpp"
#include "simcore/simulation.hpp"
#include "simcore/xml_world.hpp"
#include "targets.hpp"

using simcore::CsgError;
using simcore::CsgSolid;
using simcore::Vec3;

namespace {

bool in(const CsgSolid& s, double x, double y, double z) {
  std::optional<std::uint32_t> color;
  return s.inside(Vec3{x, y, z}, color);
}

std::string error(const std::string& text) {
  try {
    CsgSolid::parse(text);
  } catch (const CsgError& e) {
    return std::to_string(e.offset()) + ": " + e.what();
  }
  return "(no error)";
}

std::size_t blocks(const std::string& target, const std::string& grid, const std::string& csg) {
  const simcore::WorldDescription d = simcore::parseWorldXml(
      "<world gridSize=\"" + grid + "\" target=\"" + target + "\"><blockList>" + csg + "</blockList></world>",
      "w.xml");
  const auto spec = targets::makeTarget(target);
  BOOST_REQUIRE(spec);
  simcore::Simulation sim(*spec, d.grid, simcore::SimulationConfig{});
  simcore::populateSimulation(d, sim);
  return sim.world().blockCount();
}

}  // namespace

BOOST_AUTO_TEST_CASE(primitives_have_inclusive_boundaries) {
  const CsgSolid cube = CsgSolid::parse("cube([2, 3, 4]);");
  BOOST_TEST(in(cube, 0, 0, 0));
  BOOST_TEST(in(cube, 2, 3, 4));
  BOOST_TEST(!in(cube, 2.01, 1, 1));
  BOOST_TEST(!in(cube, -0.01, 1, 1));
  const CsgSolid centred = CsgSolid::parse("cube([2, 2, 2], true);");
  BOOST_TEST(in(centred, -1, -1, 1));
  BOOST_TEST(!in(centred, 1.5, 0, 0));
  const CsgSolid sphere = CsgSolid::parse("sphere(2);");
  BOOST_TEST(in(sphere, 0, 2, 0));
  BOOST_TEST(!in(sphere, 1.5, 1.5, 0));
  const CsgSolid cylinder = CsgSolid::parse("cylinder(4, 1);");
  BOOST_TEST(in(cylinder, 1, 0, 4));
  BOOST_TEST(!in(cylinder, 0, 0, -0.5));
  const CsgSolid cone = CsgSolid::parse("cylinder(4, 2, 0, true);");  // radius 2 at z = -2, 0 at z = 2
  BOOST_TEST(in(cone, 1.9, 0, -2));
  BOOST_TEST(!in(cone, 1.9, 0, 1));
  BOOST_TEST(in(cone, 0.4, 0, 1));
}

BOOST_AUTO_TEST_CASE(the_torus_measures_its_distance_in_3d_as_visiblesim_does) {
  const CsgSolid torus = CsgSolid::parse("torus(5, 1);");
  BOOST_TEST(in(torus, 5, 0, 0));
  BOOST_TEST(!in(torus, 3.5, 0, 0));
  // sqrt(x² + y² + z²) rather than sqrt(x² + y²): (4.5, 0, 0.9) is 4.589 from the centre.
  BOOST_TEST(in(torus, 4.5, 0, 0.9));
}

BOOST_AUTO_TEST_CASE(transforms_and_booleans) {
  BOOST_TEST(in(CsgSolid::parse("translate([10, 0, 0]) sphere(1);"), 10.5, 0, 0));
  BOOST_TEST(in(CsgSolid::parse("scale([2, 1, 1]) sphere(1);"), 1.9, 0, 0));
  // rotate([0, 0, 90]) turns the long side of the box from x to y.
  const CsgSolid turned = CsgSolid::parse("rotate([0, 0, 90]) cube([4, 1, 1]);");
  BOOST_TEST(in(turned, -0.5, 3.5, 0.5));
  BOOST_TEST(!in(turned, 3.5, 0.5, 0.5));
  const CsgSolid ring = CsgSolid::parse("difference() { sphere(3); sphere(2); }");
  BOOST_TEST(in(ring, 2.5, 0, 0));
  BOOST_TEST(!in(ring, 1, 0, 0));
  const CsgSolid both = CsgSolid::parse("intersection() { sphere(3); cube([5, 5, 5]); }");
  BOOST_TEST(in(both, 1, 1, 1));
  BOOST_TEST(!in(both, -1, 0, 0));
  BOOST_TEST(!in(CsgSolid::parse("intersection() { }"), 0, 0, 0));
}

BOOST_AUTO_TEST_CASE(the_outermost_color_wins) {
  const CsgSolid s =
      CsgSolid::parse("color([0, 0, 255]) union() { color([255, 0, 0]) sphere(1); cube([4, 4, 4]); }");
  std::optional<std::uint32_t> color;
  BOOST_TEST(s.inside(Vec3{0, 0, 0}, color));
  BOOST_TEST(*color == 0x0000ffu);
  std::optional<std::uint32_t> none;
  BOOST_TEST(CsgSolid::parse("sphere(1);").inside(Vec3{}, none));
  BOOST_TEST(!none.has_value());
}

BOOST_AUTO_TEST_CASE(variables_expressions_and_modules) {
  const CsgSolid s = CsgSolid::parse(
      "r = 2 ^ 2 / 2; // 2\n"
      "module ball(x, radius) { translate([x, 0, 0]) sphere(radius); }\n"
      "union() { ball(10, r); ball(-10, sqrt(max(1, 4))); }");
  BOOST_TEST(in(s, 11.9, 0, 0));
  BOOST_TEST(in(s, -8.1, 0, 0));
  BOOST_TEST(!in(s, 0, 0, 0));
  BOOST_TEST(in(CsgSolid::parse("sphere(cos(_pi) + 3);"), 1.9, 0, 0));
}

BOOST_AUTO_TEST_CASE(bounding_boxes_follow_visiblesim) {
  const simcore::CsgBox u =
      CsgSolid::parse("union() { sphere(2); translate([5, 0, 0]) cube([1, 1, 1]); }").boundingBox();
  BOOST_TEST(u.min.x == -2.0);
  BOOST_TEST(u.max.x == 6.0);
  // A difference has the box of its first child.
  BOOST_TEST(CsgSolid::parse("difference() { cube([3, 3, 3]); sphere(9); }").boundingBox().max.z == 3.0);
  // The torus box is (-r1, -r1, -r2) .. (r1, r1, r2), as VisibleSim has it.
  const simcore::CsgBox t = CsgSolid::parse("torus(5, 1);").boundingBox();
  BOOST_TEST(t.max.x == 5.0);
  BOOST_TEST(t.max.z == 1.0);
}

BOOST_AUTO_TEST_CASE(errors_point_into_the_text) {
  BOOST_TEST(error("cube([1, 1]);") == "10: expected ',', found ']'");
  BOOST_TEST(error("sphere(r);") == "7: unknown variable 'r'");
  BOOST_TEST(error("blob(1);") == "0: unknown shape 'blob'");
  BOOST_TEST(error("x = 1;") == "6: no shape (cube, sphere, cylinder, torus, union, ...)");
  BOOST_TEST(error("cube([1,1,1], maybe);") == "14: expected true or false, found 'maybe'");
  BOOST_TEST(error("sphere(1) # x") == "10: unexpected character '#'");
  BOOST_TEST(error("module m() { m(); } m();").find("nested too deeply") != std::string::npos);
  BOOST_TEST(error("sphere(" + std::string(5000, '(')).find("nested too deeply") != std::string::npos);
  std::string doubling = "module m0() { sphere(1); }\n";
  for (int i = 1; i < 40; ++i)
    doubling += "module m" + std::to_string(i) + "() { union() { m" + std::to_string(i - 1) + "(); m" +
                std::to_string(i - 1) + "(); } }\n";
  BOOST_TEST(error(doubling + "m39();").find("more than 100000 shapes") != std::string::npos);
  BOOST_TEST(error("sphere(1); cube([1,1,1]);") == "(no error)");
  BOOST_TEST(CsgSolid::parse("sphere(1); cube([1,1,1]);").warnings().size() == 1u);
}

BOOST_AUTO_TEST_CASE(worlds_get_the_cells_inside_the_moved_solid) {
  // Bounding box (0,0,0)..(2,2,2) moved to start one cell before the grid's corner: cells 1..3.
  BOOST_TEST(blocks("blinkyblocks", "5,5,5", "<csg content=\"cube([2,2,2]);\"/>") == 27u);
  // Without the offset, cells 0..2; without the bounding box either, the same here.
  BOOST_TEST(blocks("blinkyblocks", "5,5,5", "<csg content=\"cube([2,2,2]);\" offset=\"false\"/>") == 27u);
  // A centred cube of side 2 without a bounding box: cell x samples x - 1, inside for x in 0..2.
  BOOST_TEST(blocks("blinkyblocks", "5,5,5",
                    "<csg content=\"cube([2,2,2], true);\" boundingBox=\"false\"/>") == 27u);
  // Smart Blocks: the floor only (z = 0).
  BOOST_TEST(blocks("smartblocks", "6,6,1", "<csg content=\"cube([3,3,3]);\" offset=\"false\"/>") == 16u);
  // Cells given as <block> are kept and not filled twice.
  BOOST_TEST(
      blocks("blinkyblocks", "5,5,5", "<block position=\"1,1,1\"/><csg content=\"cube([2,2,2]);\"/>") == 27u);
}

BOOST_AUTO_TEST_CASE(catoms_sample_cells_where_visiblesim_puts_them) {
  const auto c2 = targets::makeTarget("catoms2d");
  const auto c3 = targets::makeTarget("catoms3d");
  BOOST_REQUIRE(c2);
  BOOST_REQUIRE(c3);
  const auto hex = c2->makeLattice();
  const Vec3 h = hex->csgPoint(simcore::Cell{2, 0, 1});
  BOOST_TEST(h.x == 2.5);
  BOOST_TEST(h.y == 2.5);
  BOOST_TEST(std::fabs(h.z - std::sqrt(3.0) / 2) < 1e-12);
  const auto fcc = c3->makeLattice();
  const Vec3 f = fcc->csgPoint(simcore::Cell{2, 3, 1});  // odd layer: +1 in x and y
  BOOST_TEST(f.x == 3.0);
  BOOST_TEST(f.y == 4.0);
  BOOST_TEST(std::fabs(f.z - 1.5 * std::sqrt(2.0) / 2) < 1e-12);
  const Vec3 e = fcc->csgPoint(simcore::Cell{2, 3, 0});  // even layer: +0.5
  BOOST_TEST(e.x == 2.5);
  BOOST_TEST(e.y == 3.5);
}

BOOST_AUTO_TEST_CASE(the_dome_example_has_the_blocks_its_comment_counts) {
  const simcore::WorldDescription d =
      simcore::loadWorldXml(std::string(MELD_SOURCE_DIR) + "/examples/worlds/blinky-csg-dome.xml");
  const auto spec = targets::makeTarget(d.target);
  BOOST_REQUIRE(spec);
  simcore::Simulation sim(*spec, d.grid, simcore::SimulationConfig{});
  simcore::populateSimulation(d, sim);
  BOOST_TEST(sim.world().blockCount() == 315u);
  std::size_t red = 0;
  for (simcore::BlockId id = 0; id < sim.world().blockCount(); ++id)
    red += sim.world().block(id).color == 0xff0000u;
  BOOST_TEST(red == 169u);
}
