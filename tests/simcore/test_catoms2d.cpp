#define BOOST_TEST_MODULE simcore_catoms2d
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <vector>

#include "catoms2d/catoms2d.hpp"
#include "catoms2d/hex_lattice.hpp"
#include "catoms2d_support.hpp"
#include "flood_check.hpp"
#include "simcore/xml_world.hpp"
#include "test_support.hpp"

using namespace simcore;
using targets::HexLattice;
using testsupport::Script;

namespace {

using namespace c2dtest;

// The centre of a cell by the VisibleSim convention, written out here rather than taken from the
// lattice: odd rows shifted by half a catom, rows sqrt(3)/2 apart.
Vec3 hexCenter(const Cell& c) { return Vec3{c.x + ((c.z & 1) ? 0.5 : 0.0), 0.0, c.z * std::sqrt(3.0) / 2.0}; }

std::unique_ptr<Simulation> makeC2D(GridSize size, const std::vector<Cell>& cells,
                                    const SimulationConfig& cfg = {}) {
  return testsupport::makeSim(targets::catoms2DTarget(), size, cells, cfg);
}

// Every cell of a w x h patch (y = 0), x fastest.
std::vector<Cell> patch(int w, int h) {
  std::vector<Cell> cells;
  for (int z = 0; z < h; ++z)
    for (int x = 0; x < w; ++x) cells.push_back(Cell{x, 0, z});
  return cells;
}

}  // namespace

// --- The lattice ---

BOOST_AUTO_TEST_CASE(neighbor_offsets_depend_on_row_parity) {
  const HexLattice lat;
  const Cell even{4, 0, 2}, odd{4, 0, 3};
  const Cell expectEven[6] = {{5, 0, 2}, {4, 0, 3}, {3, 0, 3}, {3, 0, 2}, {3, 0, 1}, {4, 0, 1}};
  const Cell expectOdd[6] = {{5, 0, 3}, {5, 0, 4}, {4, 0, 4}, {3, 0, 3}, {4, 0, 2}, {5, 0, 2}};
  BOOST_REQUIRE_EQUAL(lat.faceCount(), 6);
  for (int f = 0; f < 6; ++f) {
    BOOST_TEST_CONTEXT("face " << f) {
      BOOST_CHECK(lat.neighborCell(even, f) == expectEven[f]);
      BOOST_CHECK(lat.neighborCell(odd, f) == expectOdd[f]);
    }
  }
  // Row -1 is odd, as in the table (neighbors of the bottom row look there).
  BOOST_CHECK(lat.neighborCell(Cell{2, 0, -1}, kTopRight) == (Cell{3, 0, 0}));
}

BOOST_AUTO_TEST_CASE(faces_point_every_60_degrees_one_diameter_away) {
  const HexLattice lat;
  for (int z = -3; z <= 4; ++z)
    for (int x = -2; x <= 2; ++x)
      for (int f = 0; f < 6; ++f) {
        const Cell c{x, 0, z}, n = lat.neighborCell(c, f);
        const Vec3 a = lat.cellCenter(c), b = lat.cellCenter(n), ours = hexCenter(c);
        BOOST_TEST_CONTEXT("cell (" << x << ",0," << z << ") face " << f) {
          BOOST_CHECK(near(a.x, ours.x) && near(a.y, ours.y) && near(a.z, ours.z));
          const double angle = f * M_PI / 3.0;  // counter-clockwise from +x, in the x-z plane
          BOOST_CHECK(near(b.x - a.x, std::cos(angle)));
          BOOST_CHECK(near(b.z - a.z, std::sin(angle)));
          BOOST_CHECK(near(b.y, 0.0));
        }
      }
}

BOOST_AUTO_TEST_CASE(opposite_face_leads_back_for_every_face_and_parity) {
  const HexLattice lat;
  for (int z = -3; z <= 4; ++z)
    for (int f = 0; f < 6; ++f) {
      const Cell c{3, 0, z};
      const Cell n = lat.neighborCell(c, f);
      const int back = lat.oppositeFace(c, f);
      BOOST_TEST_CONTEXT("row " << z << " face " << f) {
        BOOST_CHECK_EQUAL(back, (f + 3) % 6);
        BOOST_CHECK(lat.neighborCell(n, back) == c);
        BOOST_CHECK_EQUAL(lat.oppositeFace(n, back), f);
      }
    }
}

BOOST_AUTO_TEST_CASE(only_the_plane_y_0_holds_catoms) {
  const HexLattice lat;
  BOOST_CHECK(lat.isValidCell(Cell{3, 0, 5}));
  BOOST_CHECK(!lat.isValidCell(Cell{3, 1, 5}));
  BOOST_CHECK(lat.isPlanar());
  Simulation sim(targets::catoms2DTarget(), GridSize{4, 2, 4});
  BOOST_CHECK_EQUAL(sim.addBlock(Cell{1, 1, 1}), kNoBlock);
  BOOST_CHECK_EQUAL(sim.addBlock(Cell{1, 0, 1}), 0u);
}

BOOST_AUTO_TEST_CASE(target_names_and_spec) {
  for (const char* name : {"catoms2d", "Catoms2D", "c2d", "C2D"}) {
    const auto t = targets::makeTarget(name);
    BOOST_REQUIRE_MESSAGE(t.has_value(), name);
    BOOST_CHECK_EQUAL(t->name, "catoms2d");
  }
  const TargetSpec t = targets::catoms2DTarget();
  BOOST_CHECK_EQUAL(t.faceNames.size(), 6u);
  BOOST_CHECK_EQUAL(t.faceNames[kTopLeft], "top-left");
  BOOST_CHECK(t.canMove() && t.motionRule && !t.canTranslate);
  BOOST_CHECK_EQUAL(t.motionDuration, kSecond);
  BOOST_CHECK_EQUAL(t.link.rateBitsPerSecond, 1e6);
  BOOST_CHECK_EQUAL(t.link.latency, 0);
  BOOST_CHECK_EQUAL(t.makeLattice()->faceCount(), 6);
}

// --- Links ---

BOOST_AUTO_TEST_CASE(full_patch_neighbor_counts_match_geometry) {
  const std::vector<Cell> cells = patch(7, 6);
  auto sim = makeC2D({7, 1, 6}, cells);
  const World& w = sim->world();
  int interior = 0;
  for (BlockId a = 0; a < cells.size(); ++a) {
    int expected = 0;
    for (const Cell& other : cells) {
      const Vec3 p = hexCenter(cells[a]), q = hexCenter(other);
      expected += near(std::hypot(p.x - q.x, p.z - q.z), 1.0);
    }
    int linked = 0;
    for (int f = 0; f < 6; ++f) {
      const BlockId b = w.neighbor(a, f);
      if (b == kNoBlock) continue;
      ++linked;
      BOOST_CHECK_EQUAL(w.neighbor(b, w.lattice().oppositeFace(w.block(a).cell, f)), a);
    }
    BOOST_CHECK_EQUAL(linked, expected);
    const Cell& c = cells[a];
    if (c.x > 0 && c.x < 6 && c.z > 0 && c.z < 5) {
      ++interior;
      BOOST_CHECK_EQUAL(linked, 6);
    }
  }
  BOOST_CHECK_EQUAL(interior, 20);
  // The block program sees the same through the ABI.
  Script s(*sim);
  std::vector<int> counts(cells.size(), -1);
  s.onStart = [&](vs_ctx* ctx) { counts[ctx->block] = ctx->api->neighbor_count(ctx); };
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(counts[0], 2);  // (0,0,0): right, top-right
  BOOST_CHECK_EQUAL(counts[6], 3);  // (6,0,0), right end of an even row: top-right, top-left, left
  BOOST_CHECK_EQUAL(counts[7], 5);  // (0,0,1), left end of an odd row: all but left
}

BOOST_AUTO_TEST_CASE(removing_a_catom_breaks_its_six_links_on_opposite_faces) {
  auto sim = makeC2D({3, 1, 3}, patch(3, 3));
  Script s(*sim);
  const BlockId centre = 4;  // (1,0,1), an odd row
  testsupport::checkRemovalBreaksEveryLink(*sim, s, centre, 6, [](int f) { return (f + 3) % 6; });
}

BOOST_AUTO_TEST_CASE(messages_arrive_on_the_opposite_face) {
  // (2,0,1) is odd: its top-left neighbor (2,0,2) hears it on its bottom-right face.
  auto sim = makeC2D({5, 1, 4}, {{2, 0, 1}, {2, 0, 2}});
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) BOOST_CHECK_EQUAL(ctx->api->send(ctx, kTopLeft, "hi", 2, 0), VS_OK);
  };
  sim->runUntilEmpty();
  const auto got = s.of(1, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(got.size(), 1u);
  BOOST_CHECK_EQUAL(got[0].face, kBottomRight);
  BOOST_CHECK_EQUAL(got[0].other, 0u);
  BOOST_CHECK_EQUAL(got[0].time, 16 * kMicrosecond);  // 2 bytes at 1 Mbit/s
}

// --- World files and the flood example ---

BOOST_AUTO_TEST_CASE(example_worlds_load) {
  const auto patchWorld = loadWorldXml(floodcheck::kWorlds + "catoms2d-patch.xml");
  BOOST_TEST(patchWorld.warnings.empty());
  BOOST_TEST(patchWorld.target == "catoms2d");
  BOOST_TEST(patchWorld.blocks.size() == 30u);
  BOOST_TEST((patchWorld.blocks[29].cell == Cell{7, 0, 5}));
  const auto line = loadWorldXml(floodcheck::kWorlds + "catoms2d-line.xml");
  BOOST_TEST(line.warnings.empty());
  BOOST_TEST(line.blocks.size() == 12u);
  BOOST_TEST((line.blocks[11].cell == Cell{13, 0, 0}));
}

BOOST_AUTO_TEST_CASE(a_cell_off_the_plane_is_an_error_at_its_element) {
  const std::string text =
      "<world gridSize=\"4,2,4\" target=\"catoms2d\">\n"
      "  <blockList>\n"
      "    <block position=\"1,0,1\"/>\n"
      "    <block position=\"2,1,1\"/>\n"
      "  </blockList>\n"
      "</world>\n";
  const WorldDescription d = parseWorldXml(text, "c2d.xml");
  Simulation sim(*targets::makeTarget(d.target), d.grid);
  try {
    populateSimulation(d, sim);
    BOOST_FAIL("no error");
  } catch (const XmlWorldError& e) {
    BOOST_TEST(std::string(e.what()) ==
               "c2d.xml:4:5: error: cell (2,1,1) is not a cell of the hexagonal lattice");
  }
}

BOOST_AUTO_TEST_CASE(color_flood_reaches_every_catom_at_its_hop_distance) {
  // The patch: block 0 floods at t = 0 (checked before the tap at 1 s), then block 29's wave.
  BOOST_TEST(floodcheck::checkFlood("catoms2d-patch.xml", hexCenter, kSecond / 2, 0, 1) == 30u);
  BOOST_TEST(floodcheck::checkFlood("catoms2d-patch.xml", hexCenter, kTimeInfinity, 29, 2) == 30u);
  BOOST_TEST(floodcheck::checkFlood("catoms2d-line.xml", hexCenter, kTimeInfinity, 0, 1) == 12u);
}
