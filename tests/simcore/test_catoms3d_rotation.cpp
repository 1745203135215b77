#define BOOST_TEST_MODULE simcore_catoms3d_rotation
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <vector>

#include "catoms3d/catoms3d.hpp"
#include "catoms3d/fcc_lattice.hpp"
#include "catoms3d/rotation_rule.hpp"
#include "test_support.hpp"

// The Catoms 3D motion (targets/catoms3d/rotation_rule.hpp): a 60-degree rotation over a pivot's
// surface, through the triangle or the square of the pivot's cuboctahedron of neighbors.
//
// The worked example every case starts from, in the even layer z = 2 (directions from A: side0
// (1,0,0), top2 (.5,.5,h), top3 (-.5,.5,h), top5 (.5,-.5,h), side6 (-1,0,0), bottom10 (.5,.5,-h),
// h = sqrt(2)/2): A = (2,2,2) rotates around P = (3,2,2) (A's side0) into B = (2,2,3) (A's top2).
//   triangle: K, the neighbor of A one unit from both P and B, is top5 -> (2,1,3);
//   square:   D = bottom10 -> (2,2,1) (one unit from P, sqrt 2 from B) and C = B + bottom10 of an
//             odd layer (+1,+1,-1) -> (3,3,2), one unit from P;
//   both:     2A - P = A's side6 -> (1,2,2), and 2B - P = B + (B - P) = B + top3 (odd: 0,1,1) -> (2,3,4).

using namespace simcore;
using testsupport::Script;
using namespace targets;

namespace {

const Cell kA{2, 2, 2}, kP{3, 2, 2}, kB{2, 2, 3};
const Cell kK{2, 1, 3}, kD{2, 2, 1}, kC{3, 3, 2}, kBeyondA{1, 2, 2}, kBeyondB{2, 3, 4};

bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }
constexpr std::uint16_t bit(int f) { return std::uint16_t(1u << f); }

std::unique_ptr<Simulation> makeC3D(GridSize size, const std::vector<Cell>& cells) {
  return testsupport::makeSim(catoms3DTarget(), size, cells);
}

// Block 0 tries move(face) at start (through `s`, the program of `sim`); returns the code.
int tryMove(Simulation& sim, Script& s, int face) {
  int rc = 99;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) rc = ctx->api->move(ctx, face);
  };
  sim.runUntil(1);
  return rc;
}

}  // namespace

BOOST_AUTO_TEST_CASE(the_rule_table_matches_the_worked_example) {
  const FccRotationRule rule;
  const auto& r = rule.rotations(kC3DTop2);
  // Pivots in face order: side0, side1, top3, top5 (the four neighbors of A one unit from B).
  BOOST_CHECK_EQUAL(r[0].pivotFace, kC3DSide0);
  BOOST_CHECK_EQUAL(r[2].pivotFace, kC3DSide1);
  BOOST_CHECK_EQUAL(r[4].pivotFace, kC3DTop3);
  BOOST_CHECK_EQUAL(r[6].pivotFace, kC3DTop5);
  BOOST_CHECK(!r[0].throughSquare && r[1].throughSquare);
  BOOST_CHECK_EQUAL(r[0].fromFaces, bit(kC3DSide6) | bit(kC3DTop5));
  BOOST_CHECK_EQUAL(r[0].toFaces, bit(kC3DTop3));
  BOOST_CHECK_EQUAL(r[1].fromFaces, bit(kC3DSide6) | bit(kC3DBottom10));
  BOOST_CHECK_EQUAL(r[1].toFaces, bit(kC3DTop3) | bit(kC3DBottom10));
  // The same cells through the lattice, in both parities of the faces' offsets.
  const FccLattice lat;
  BOOST_CHECK(lat.neighborCell(kA, kC3DTop5) == kK);
  BOOST_CHECK(lat.neighborCell(kA, kC3DBottom10) == kD);
  BOOST_CHECK(lat.neighborCell(kB, kC3DBottom10) == kC);
  BOOST_CHECK(lat.neighborCell(kB, kC3DTop3) == kBeyondB);
  // Every rotation of every face: pivot one unit from the destination, the cells to free distinct
  // from origin, pivot and destination.
  for (int f = 0; f < 12; ++f)
    for (const auto& rot : rule.rotations(f)) {
      const Cell to = lat.neighborCell(kA, f), pivot = lat.neighborCell(kA, rot.pivotFace);
      const Vec3 d{lat.cellCenter(to).x - lat.cellCenter(pivot).x, lat.cellCenter(to).y - lat.cellCenter(pivot).y,
                   lat.cellCenter(to).z - lat.cellCenter(pivot).z};
      BOOST_CHECK(near(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 1.0));
      forEachSweptCell(lat, kA, to, rot.fromFaces, rot.toFaces, [&](const Cell& c) {
        BOOST_CHECK(!(c == kA) && !(c == to) && !(c == pivot));
      });
      BOOST_CHECK_EQUAL(__builtin_popcount(rot.fromFaces) + __builtin_popcount(rot.toFaces), rot.throughSquare ? 4 : 3);
    }
}

BOOST_AUTO_TEST_CASE(rotation_over_the_triangle_follows_the_pivot_and_relinks) {
  auto sim = makeC3D({6, 6, 6}, {kA, kP});
  Script s(*sim);
  int rc = 99;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) rc = ctx->api->move(ctx, kC3DTop2);
  };
  sim->runUntil(kSecond / 2);
  BOOST_CHECK_EQUAL(rc, VS_OK);
  const World& w = sim->world();
  for (const Cell& c : {kA, kB, kK, kBeyondA, kBeyondB}) BOOST_CHECK_EQUAL(w.anyAt(c), 0u);
  BOOST_CHECK(w.isFree(kD) && w.isFree(kC));  // the square is not used
  // Half way: one diameter from P's centre, in the direction of A + B - 2P.
  const FccLattice lat;
  const Vec3 p = sim->position(0), pc = lat.cellCenter(kP), ac = lat.cellCenter(kA), bc = lat.cellCenter(kB);
  const Vec3 m{ac.x + bc.x - 2 * pc.x, ac.y + bc.y - 2 * pc.y, ac.z + bc.z - 2 * pc.z};
  const double lm = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
  BOOST_CHECK_MESSAGE(near(p.x, pc.x + m.x / lm) && near(p.y, pc.y + m.y / lm) && near(p.z, pc.z + m.z / lm),
                      "half way: " << p.x << ", " << p.y << ", " << p.z);
  sim->runUntilEmpty();
  BOOST_CHECK(w.block(0).cell == kB);
  for (const Cell& c : {kA, kK, kBeyondA, kBeyondB}) BOOST_CHECK(w.isFree(c));
  // P is behind B's bottom9 (direction (.5,-.5,-h)), and B behind P's top3.
  BOOST_CHECK_EQUAL(w.neighbor(0, kC3DBottom9), 1u);
  BOOST_CHECK_EQUAL(w.neighbor(1, kC3DTop3), 0u);
  BOOST_CHECK_EQUAL(s.of(0, VS_EV_MOTION_END).size(), 1u);
}

BOOST_AUTO_TEST_CASE(a_blocked_triangle_leaves_the_square) {
  auto sim = makeC3D({6, 6, 6}, {kA, kP, kK});
  Script s(*sim);
  BOOST_CHECK_EQUAL(tryMove(*sim, s, kC3DTop2), VS_OK);
  const World& w = sim->world();
  for (const Cell& c : {kD, kC, kBeyondA, kBeyondB}) BOOST_CHECK_EQUAL(w.anyAt(c), 0u);
  sim->runUntilEmpty();
  BOOST_CHECK(w.block(0).cell == kB);
}

BOOST_AUTO_TEST_CASE(blocked_rotations_are_refused_and_change_nothing) {
  struct Case {
    const char* what;
    std::vector<Cell> cells;  // block 0 tries move(face)
    int face, expected;
  };
  const Case cases[] = {
      {"destination occupied", {kA, kP, kB}, kC3DTop2, VS_ERR_CELL_OCCUPIED},
      {"destination outside the grid", {{2, 2, 5}, {3, 2, 5}}, kC3DTop2, VS_ERR_OUT_OF_WORLD},
      {"no neighbor at all", {kA}, kC3DTop2, VS_ERR_NO_NEIGHBOR},
      // A neighbor behind side6 is two units from B: it touches A only.
      {"neighbor not next to the destination", {kA, kBeyondA}, kC3DTop2, VS_ERR_NO_NEIGHBOR},
      // A module on A's far side (2A - P) blocks both ways around P; it touches nothing near B.
      {"cell beyond the origin taken", {kA, kP, kBeyondA}, kC3DTop2, VS_ERR_CELL_OCCUPIED},
      {"cell beyond the destination taken", {kA, kP, kBeyondB}, kC3DTop2, VS_ERR_CELL_OCCUPIED},
      // K blocks the triangle and D the square around P; K is a pivot itself (one unit from B),
      // but its triangle needs P's cell and its square (2,2,4), which is taken too.
      {"triangle and square both blocked", {kA, kP, kK, kD, {2, 2, 4}}, kC3DTop2, VS_ERR_CELL_OCCUPIED},
      {"face too large", {kA, kP}, 12, VS_ERR_BAD_FACE},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.what) {
      auto sim = makeC3D({6, 6, 6}, c.cells);
      Script s(*sim);
      BOOST_CHECK_EQUAL(tryMove(*sim, s, c.face), c.expected);
      BOOST_CHECK_EQUAL(sim->statistics().motionsStarted, 0u);
      for (BlockId b = 0; b < c.cells.size(); ++b) BOOST_CHECK_EQUAL(sim->world().settledAt(c.cells[b]), b);
    }
  }
}

BOOST_AUTO_TEST_CASE(around_the_other_pivot_through_its_square) {
  // K and D taken: around P both ways are blocked, but K is one unit from B and its square (D' =
  // A's top4 -> (1,1,3), C' = B's top4 -> (2,2,4), beyond A = A's bottom11 -> (1,2,1), beyond B = B's
  // side1 -> (2,3,3)) is free.
  auto sim = makeC3D({6, 6, 6}, {kA, kP, kK, kD});
  Script s(*sim);
  BOOST_CHECK_EQUAL(tryMove(*sim, s, kC3DTop2), VS_OK);
  const World& w = sim->world();
  for (const Cell& c : {Cell{1, 1, 3}, Cell{2, 2, 4}, Cell{1, 2, 1}, Cell{2, 3, 3}}) BOOST_CHECK_EQUAL(w.anyAt(c), 0u);
  BOOST_CHECK(w.isFree(kBeyondB) && w.isFree(kBeyondA));
  sim->runUntilEmpty();
  BOOST_CHECK(w.block(0).cell == kB);
  BOOST_CHECK_EQUAL(w.neighbor(0, kC3DBottom9), 1u);  // still next to P as well
}

BOOST_AUTO_TEST_CASE(cells_outside_the_grid_do_not_block) {
  // At x = 0 the cell beyond A, (-1,2,2), is outside: nothing can be there.
  auto sim = makeC3D({6, 6, 6}, {{0, 2, 2}, {1, 2, 2}});
  Script s(*sim);
  BOOST_CHECK_EQUAL(tryMove(*sim, s, kC3DTop2), VS_OK);
  sim->runUntilEmpty();
  BOOST_CHECK(sim->world().block(0).cell == (Cell{0, 2, 3}));
}

BOOST_AUTO_TEST_CASE(a_reserved_cell_blocks_another_rotation_until_the_first_ends) {
  // Block 0 rotates A -> B around P, reserving K. Block 2 at X = (1,1,3) (odd) wants K, its side0,
  // around block 3 at (2,1,2) (its bottom9): refused while block 0 rotates, allowed after (through
  // the triangle, whose third cell is A's, free by then).
  auto sim = makeC3D({6, 6, 6}, {kA, kP, {1, 1, 3}, {2, 1, 2}});
  Script s(*sim);
  std::vector<std::pair<BlockId, int>> codes;
  testsupport::competeForACell(s, kC3DTop2, kC3DSide0, codes);
  sim->runUntilEmpty();
  const std::vector<std::pair<BlockId, int>> expected = {{0, VS_OK}, {2, VS_ERR_CELL_OCCUPIED}, {2, VS_OK}};
  BOOST_CHECK(codes == expected);
  BOOST_CHECK(sim->world().block(2).cell == kK);
}

BOOST_AUTO_TEST_CASE(random_rotations_keep_the_world_consistent_and_deterministic) {
  std::vector<Cell> cells;
  for (int z = 1; z < 7; ++z)
    for (int y = 1; y < 7; ++y)
      for (int x = 1; x < 7; ++x)
        if ((x + 2 * y + 3 * z) % 4 != 0) cells.push_back(Cell{x, y, z});
  testsupport::checkRandomWalk(catoms3DTarget(), {8, 8, 8}, cells, 7);
}
