#define BOOST_TEST_MODULE simcore_catoms3d
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "catoms3d/catoms3d.hpp"
#include "catoms3d/fcc_lattice.hpp"
#include "flood_check.hpp"
#include "simcore/xml_world.hpp"
#include "test_support.hpp"

using namespace simcore;
using targets::FccLattice;
using testsupport::Script;

namespace {

bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }

// The centre of a cell by the VisibleSim convention, written out here rather than taken from the
// lattice: odd layers shifted by half a cell in x and y, layers sqrt(2)/2 apart.
Vec3 fccCenter(const Cell& c) {
  const double shift = (c.z & 1) ? 0.5 : 0.0;
  return Vec3{c.x + shift, c.y + shift, c.z * std::sqrt(2.0) / 2.0};
}

std::unique_ptr<Simulation> makeC3D(GridSize size, const std::vector<Cell>& cells) {
  return testsupport::makeSim(targets::catoms3DTarget(), size, cells);
}

std::vector<Cell> box(int n) {
  std::vector<Cell> cells;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) cells.push_back(Cell{x, y, z});
  return cells;
}

}  // namespace

// --- The lattice ---

BOOST_AUTO_TEST_CASE(neighbor_offsets_depend_on_layer_parity) {
  const FccLattice lat;
  BOOST_REQUIRE_EQUAL(lat.faceCount(), 12);
  const Cell even[12] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},    {-1, 0, 1},  {-1, -1, 1}, {0, -1, 1},
                         {-1, 0, 0}, {0, -1, 0}, {-1, -1, -1}, {0, -1, -1}, {0, 0, -1},  {-1, 0, -1}};
  const Cell odd[12] = {{1, 0, 0},  {0, 1, 0},  {1, 1, 1},  {0, 1, 1},  {0, 0, 1},  {1, 0, 1},
                        {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {1, 0, -1}, {1, 1, -1}, {0, 1, -1}};
  const Cell e{5, 5, 4}, o{5, 5, 3};
  for (int f = 0; f < 12; ++f) {
    BOOST_TEST_CONTEXT("face " << f) {
      BOOST_CHECK(lat.neighborCell(e, f) == (Cell{e.x + even[f].x, e.y + even[f].y, e.z + even[f].z}));
      BOOST_CHECK(lat.neighborCell(o, f) == (Cell{o.x + odd[f].x, o.y + odd[f].y, o.z + odd[f].z}));
    }
  }
  // Layer -1 is odd (neighbors of the bottom layer look there).
  BOOST_CHECK(lat.neighborCell(Cell{2, 2, -1}, targets::kC3DTop4) == (Cell{2, 2, 0}));
}

BOOST_AUTO_TEST_CASE(connectors_point_the_same_way_in_both_parities_one_diameter_away) {
  const FccLattice lat;
  const double h = std::sqrt(2.0) / 2.0;
  // Connector directions (dx, dy, dz) as documented in fcc_lattice.hpp.
  const Vec3 dir[12] = {{1, 0, 0},  {0, 1, 0},  {.5, .5, h},    {-.5, .5, h},  {-.5, -.5, h}, {.5, -.5, h},
                        {-1, 0, 0}, {0, -1, 0}, {-.5, -.5, -h}, {.5, -.5, -h}, {.5, .5, -h},  {-.5, .5, -h}};
  for (int z = -3; z <= 4; ++z)
    for (int f = 0; f < 12; ++f) {
      const Cell c{2, -1, z}, n = lat.neighborCell(c, f);
      const Vec3 a = lat.cellCenter(c), b = lat.cellCenter(n), ours = fccCenter(c);
      BOOST_TEST_CONTEXT("layer " << z << " connector " << f) {
        BOOST_CHECK(near(a.x, ours.x) && near(a.y, ours.y) && near(a.z, ours.z));
        BOOST_CHECK(near(b.x - a.x, dir[f].x) && near(b.y - a.y, dir[f].y) && near(b.z - a.z, dir[f].z));
        BOOST_CHECK(near(std::sqrt(dir[f].x * dir[f].x + dir[f].y * dir[f].y + dir[f].z * dir[f].z), 1.0));
      }
    }
}

BOOST_AUTO_TEST_CASE(opposite_connector_leads_back_for_every_face_and_parity) {
  const FccLattice lat;
  for (int z = -3; z <= 4; ++z) {
    std::set<std::tuple<int, int, int>> seen;
    for (int f = 0; f < 12; ++f) {
      const Cell c{3, 3, z};
      const Cell n = lat.neighborCell(c, f);
      const int back = lat.oppositeFace(c, f);
      seen.emplace(n.x, n.y, n.z);
      BOOST_TEST_CONTEXT("layer " << z << " connector " << f) {
        BOOST_CHECK_EQUAL(back, (f + 6) % 12);
        BOOST_CHECK(lat.neighborCell(n, back) == c);
        BOOST_CHECK_EQUAL(lat.oppositeFace(n, back), f);
      }
    }
    BOOST_CHECK_EQUAL(seen.size(), 12u);  // twelve distinct neighbors
  }
}

BOOST_AUTO_TEST_CASE(target_names_and_spec) {
  for (const char* name : {"catoms3d", "Catoms3D", "c3d", "C3D"}) {
    const auto t = targets::makeTarget(name);
    BOOST_REQUIRE_MESSAGE(t.has_value(), name);
    BOOST_CHECK_EQUAL(t->name, "catoms3d");
  }
  const TargetSpec t = targets::catoms3DTarget();
  BOOST_CHECK_EQUAL(t.faceNames.size(), 12u);
  BOOST_CHECK_EQUAL(t.faceNames[targets::kC3DBottom11], "bottom11");
  BOOST_CHECK(t.canMove() && !t.canTranslate);
  BOOST_CHECK_EQUAL(std::string(t.motionRule->name()), "fcc-rotation");
  BOOST_CHECK_EQUAL(t.link.rateBitsPerSecond, 1e6);
  BOOST_CHECK_EQUAL(t.makeLattice()->faceCount(), 12);
  BOOST_CHECK(!t.makeLattice()->isPlanar());
}

// --- Links ---

BOOST_AUTO_TEST_CASE(fcc_cluster_neighbor_counts_match_geometry) {
  const std::vector<Cell> cells = box(5);
  auto sim = makeC3D({5, 5, 5}, cells);
  const World& w = sim->world();
  int twelve = 0;
  for (BlockId a = 0; a < cells.size(); ++a) {
    int expected = 0;
    for (const Cell& other : cells) {
      const Vec3 p = fccCenter(cells[a]), q = fccCenter(other);
      expected += near(
          std::sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z)), 1.0);
    }
    int linked = 0;
    for (int f = 0; f < 12; ++f) {
      const BlockId b = w.neighbor(a, f);
      if (b == kNoBlock) continue;
      ++linked;
      BOOST_CHECK_EQUAL(w.neighbor(b, (f + 6) % 12), a);
    }
    BOOST_CHECK_EQUAL(linked, expected);
    twelve += linked == 12;
  }
  // Fully surrounded: layers z = 1..3 (someone above and below), x and y in 1..3 (side neighbors
  // on both sides; the shifted layers then cover the four above and below too): 9 per layer.
  BOOST_CHECK_EQUAL(twelve, 3 * 9);
  Script s(*sim);
  std::vector<int> counts(cells.size(), -1);
  s.onStart = [&](vs_ctx* ctx) { counts[ctx->block] = ctx->api->neighbor_count(ctx); };
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(counts[0], 3);    // (0,0,0): side0, side1, top2
  BOOST_CHECK_EQUAL(counts[31], 12);  // (1,1,1)
}

BOOST_AUTO_TEST_CASE(removing_a_catom_breaks_its_twelve_links_on_opposite_connectors) {
  auto sim = makeC3D({3, 3, 3}, box(3));
  Script s(*sim);
  const BlockId centre = 13;  // (1,1,1), an odd layer: all twelve neighbors are in the box
  testsupport::checkRemovalBreaksEveryLink(*sim, s, centre, 12, [](int f) { return (f + 6) % 12; });
}

BOOST_AUTO_TEST_CASE(messages_cross_layers_on_the_opposite_connector) {
  // (2,2,2) even; its top3 neighbor is (1,2,3), which hears it on bottom9.
  auto sim = makeC3D({4, 4, 4}, {{2, 2, 2}, {1, 2, 3}});
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) BOOST_CHECK_EQUAL(ctx->api->send(ctx, targets::kC3DTop3, "x", 1, 0), VS_OK);
    if (ctx->block == 1) BOOST_CHECK_EQUAL(ctx->api->neighbor(ctx, targets::kC3DBottom9), 0u);
  };
  sim->runUntilEmpty();
  const auto got = s.of(1, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(got.size(), 1u);
  BOOST_CHECK_EQUAL(got[0].face, targets::kC3DBottom9);
  BOOST_CHECK_EQUAL(got[0].other, 0u);
}

// --- World files and the flood example ---

BOOST_AUTO_TEST_CASE(example_worlds_load) {
  const auto pyramid = loadWorldXml(floodcheck::kWorlds + "catoms3d-pyramid.xml");
  BOOST_TEST(pyramid.warnings.empty());
  BOOST_TEST(pyramid.target == "catoms3d");
  BOOST_REQUIRE(pyramid.blocks.size() == 14u);
  BOOST_TEST((pyramid.blocks[13].cell == Cell{2, 2, 2}));
  BOOST_TEST(pyramid.taps.size() == 1u);
  const auto big = loadWorldXml(floodcheck::kWorlds + "catoms3d-box.xml");
  BOOST_TEST(big.warnings.empty());
  BOOST_REQUIRE(big.blocks.size() == 1000u);
  BOOST_TEST((big.blocks[999].cell == Cell{10, 10, 10}));
  // The apex of the pyramid touches the four catoms of the middle layer, and only them.
  Simulation sim(*targets::makeTarget(pyramid.target), pyramid.grid);
  populateSimulation(pyramid, sim);
  std::set<BlockId> apex;
  for (int f = 0; f < 12; ++f)
    if (sim.world().neighbor(13, f) != kNoBlock) apex.insert(sim.world().neighbor(13, f));
  BOOST_TEST((apex == std::set<BlockId>{9, 10, 11, 12}));
}

BOOST_AUTO_TEST_CASE(bad_positions_are_errors_at_file_line_col) {
  const auto error = [](const std::string& blocks) {
    try {
      parseWorldXml("<world gridSize=\"4,4,4\" target=\"catoms3d\">\n  <blockList>\n" + blocks +
                        "  </blockList>\n</world>\n",
                    "c3d.xml");
    } catch (const XmlWorldError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  BOOST_TEST(error("    <block position=\"1,1,4\"/>\n") ==
             "c3d.xml:3:12: error: attribute 'position' of <block>: \"1,1,4\" is outside the grid 4x4x4");
  BOOST_TEST(error("    <block position=\"1,1,1\"/>\n    <block position=\"1, 1, 1\"/>\n") ==
             "c3d.xml:4:12: error: <block>: cell (1,1,1) already holds block 0 (line 3)");
}

BOOST_AUTO_TEST_CASE(color_flood_reaches_every_catom_at_its_hop_distance) {
  // The pyramid: block 0's wave (checked before the tap at 1 s), then the apex's.
  BOOST_TEST(floodcheck::checkFlood("catoms3d-pyramid.xml", fccCenter, kSecond / 2, 0, 1) == 14u);
  BOOST_TEST(floodcheck::checkFlood("catoms3d-pyramid.xml", fccCenter, kTimeInfinity, 13, 2) == 14u);
  BOOST_TEST(floodcheck::checkFlood("catoms3d-box.xml", fccCenter, kTimeInfinity, 0, 1) == 1000u);
}
