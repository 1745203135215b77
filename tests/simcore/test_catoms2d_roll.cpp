#define BOOST_TEST_MODULE simcore_catoms2d_roll
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <vector>

#include "catoms2d/catoms2d.hpp"
#include "catoms2d_support.hpp"
#include "test_support.hpp"

// The Catoms 2D motion (targets/catoms2d/rotation_rule.hpp): a 60-degree roll around a pivot into
// the cell behind the face given to move(), legal when the destination and the swept cell are free.

using namespace simcore;
using testsupport::Rec;
using testsupport::Script;

namespace {

using namespace c2dtest;

std::unique_ptr<Simulation> makeC2D(GridSize size, const std::vector<Cell>& cells,
                                    const SimulationConfig& cfg = {}) {
  return testsupport::makeSim(targets::catoms2DTarget(), size, cells, cfg);
}

}  // namespace

BOOST_AUTO_TEST_CASE(roll_over_a_pivot_follows_the_arc_and_relinks) {
  // A = 0 on the floor at (1,0,0), pivot P = 1 at (2,0,0), C = 2 at (3,0,0). A rolls clockwise over
  // P: first into (1,0,1) (top-right; swept cell (0,0,1)), then onto P's top into (2,0,1)
  // (its right; swept cell (2,0,2)), where it touches P and C.
  auto sim = makeC2D({6, 1, 4}, {{1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
  Script s(*sim);
  const SimTime t0 = 100 * kMillisecond;
  std::vector<int> codes;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) ctx->api->set_timer(ctx, t0, 0, nullptr);
  };
  // The second roll starts 100 ms after the first one ends.
  s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
    if (ctx->block != 0) return;
    if (ev.kind == VS_EV_TIMER) codes.push_back(ctx->api->move(ctx, codes.empty() ? kTopRight : kRight));
    if (ev.kind == VS_EV_MOTION_END && codes.size() == 1) ctx->api->set_timer(ctx, t0, 0, nullptr);
  };
  sim->runUntil(t0 + kSecond / 2);
  // Half way: on the circle around P's centre (2,0,0), at 150 degrees — not on the chord.
  const Vec3 p = sim->position(0);
  BOOST_CHECK_MESSAGE(near(p.x, 2.0 + std::cos(5 * M_PI / 6)) && near(p.z, 0.5) && near(p.y, 0.0),
                      "half way: " << p.x << ", " << p.y << ", " << p.z);
  const World& w = sim->world();
  BOOST_CHECK_EQUAL(w.anyAt(Cell{1, 0, 1}), 0u);  // destination reserved
  BOOST_CHECK_EQUAL(w.anyAt(Cell{0, 0, 1}), 0u);  // swept cell reserved
  BOOST_CHECK_EQUAL(w.anyAt(Cell{1, 0, 0}), 0u);  // origin reserved until the end
  BOOST_CHECK_EQUAL(w.neighbor(1, kLeft), kNoBlock);
  sim->runUntil(t0 + kSecond + t0 / 2);
  BOOST_CHECK(w.block(0).cell == (Cell{1, 0, 1}));
  BOOST_CHECK(w.isFree(Cell{0, 0, 1}) && w.isFree(Cell{1, 0, 0}));
  BOOST_CHECK_EQUAL(w.neighbor(0, kBottomRight), 1u);
  BOOST_CHECK_EQUAL(w.neighbor(1, kTopLeft), 0u);
  sim->runUntilEmpty();
  BOOST_CHECK((codes == std::vector<int>{VS_OK, VS_OK}));
  BOOST_CHECK(w.block(0).cell == (Cell{2, 0, 1}));
  BOOST_CHECK_EQUAL(w.neighbor(0, kBottomLeft), 1u);
  BOOST_CHECK_EQUAL(w.neighbor(0, kBottomRight), 2u);
  BOOST_CHECK_EQUAL(w.neighbor(2, kTopLeft), 0u);
  const Vec3 end = sim->position(0);
  BOOST_CHECK(near(end.x, 2.5) && near(end.z, std::sqrt(3.0) / 2));
  // Notifications, in order: links break when a roll starts and form when it ends.
  std::vector<Rec> notes;
  for (const Rec& r : s.log)
    if (r.kind == VS_EV_NEIGHBOR_ADDED || r.kind == VS_EV_NEIGHBOR_REMOVED) notes.push_back(r);
  struct Expect {
    SimTime t;
    BlockId block;
    int kind, face;
    BlockId other;
  };
  const SimTime t1 = t0 + kSecond, t2 = t1 + t0 + kSecond;
  const Expect expected[] = {{t0, 0, VS_EV_NEIGHBOR_REMOVED, kRight, 1},
                             {t0, 1, VS_EV_NEIGHBOR_REMOVED, kLeft, 0},
                             {t1, 0, VS_EV_NEIGHBOR_ADDED, kBottomRight, 1},
                             {t1, 1, VS_EV_NEIGHBOR_ADDED, kTopLeft, 0},
                             {t1 + t0, 0, VS_EV_NEIGHBOR_REMOVED, kBottomRight, 1},
                             {t1 + t0, 1, VS_EV_NEIGHBOR_REMOVED, kTopLeft, 0},
                             {t2, 0, VS_EV_NEIGHBOR_ADDED, kBottomLeft, 1},
                             {t2, 1, VS_EV_NEIGHBOR_ADDED, kTopRight, 0},
                             {t2, 0, VS_EV_NEIGHBOR_ADDED, kBottomRight, 2},
                             {t2, 2, VS_EV_NEIGHBOR_ADDED, kTopLeft, 0}};
  BOOST_REQUIRE_EQUAL(notes.size(), std::size(expected));
  for (std::size_t i = 0; i < notes.size(); ++i) {
    BOOST_TEST_CONTEXT("notification " << i) {
      BOOST_CHECK_EQUAL(notes[i].time, expected[i].t);
      BOOST_CHECK_EQUAL(notes[i].block, expected[i].block);
      BOOST_CHECK_EQUAL(notes[i].kind, expected[i].kind);
      BOOST_CHECK_EQUAL(notes[i].face, expected[i].face);
      BOOST_CHECK_EQUAL(notes[i].other, expected[i].other);
    }
  }
  BOOST_CHECK_EQUAL(sim->statistics().motionsEnded, 2u);
}

BOOST_AUTO_TEST_CASE(roll_duration_is_configurable) {
  SimulationConfig cfg;
  cfg.motionDuration = 250 * kMillisecond;
  auto sim = makeC2D({4, 1, 3}, {{1, 0, 0}, {2, 0, 0}}, cfg);
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) BOOST_CHECK_EQUAL(ctx->api->move(ctx, kTopRight), VS_OK);
  };
  sim->runUntilEmpty();
  const auto ends = s.of(0, VS_EV_MOTION_END);
  BOOST_REQUIRE_EQUAL(ends.size(), 1u);
  BOOST_CHECK_EQUAL(ends[0].time, 250 * kMillisecond);
}

BOOST_AUTO_TEST_CASE(illegal_rolls_are_refused_and_change_nothing) {
  struct Case {
    const char* what;
    std::vector<Cell> cells;  // block 0 tries to move
    int face;
    int expected;
  };
  const Case cases[] = {
      {"destination occupied", {{1, 0, 0}, {2, 0, 0}}, kRight, VS_ERR_CELL_OCCUPIED},
      // Destination (1,0,1) free, but the catoms on both sides of it are each other's swept cell.
      {"swept cell occupied", {{1, 0, 0}, {2, 0, 0}, {0, 0, 1}}, kTopRight, VS_ERR_CELL_OCCUPIED},
      {"no neighbor at all", {{1, 0, 1}}, kTopRight, VS_ERR_NO_NEIGHBOR},
      // A neighbor on the left is no pivot for a roll to the right: it touches only the mover.
      {"neighbor not next to the destination", {{2, 0, 1}, {1, 0, 1}}, kRight, VS_ERR_NO_NEIGHBOR},
      {"destination below the grid", {{1, 0, 0}, {2, 0, 0}}, kBottomRight, VS_ERR_OUT_OF_WORLD},
      // Rolling right around a catom on its top-right would sweep (1,0,-1), under the grid.
      {"swept cell below the grid", {{1, 0, 0}, {1, 0, 1}}, kRight, VS_ERR_OUT_OF_WORLD},
      {"face too large", {{1, 0, 0}, {2, 0, 0}}, 6, VS_ERR_BAD_FACE},
      {"negative face", {{1, 0, 0}, {2, 0, 0}}, -1, VS_ERR_BAD_FACE},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.what) {
      auto sim = makeC2D({5, 1, 4}, c.cells);
      Script s(*sim);
      int rc = 99;
      s.onStart = [&](vs_ctx* ctx) {
        if (ctx->block == 0) rc = ctx->api->move(ctx, c.face);
      };
      sim->runUntilEmpty();
      BOOST_CHECK_EQUAL(rc, c.expected);
      BOOST_CHECK_EQUAL(sim->statistics().motionsStarted, 0u);
      BOOST_CHECK(sim->world().block(0).cell == c.cells[0]);
      BOOST_CHECK_EQUAL(s.count(VS_EV_NEIGHBOR_REMOVED), 0u);
      for (BlockId b = 0; b < c.cells.size(); ++b) BOOST_CHECK_EQUAL(sim->world().settledAt(c.cells[b]), b);
    }
  }
}

BOOST_AUTO_TEST_CASE(swept_cell_stays_reserved_during_the_roll) {
  // A = 0 at (2,0,0) rolls around P = 1 at (3,0,0) into (2,0,1), sweeping (1,0,1). B = 2 at (1,0,2)
  // wants (1,0,1) too, rolling around C = 3 at (0,0,1): refused while A rolls, allowed after.
  auto sim = makeC2D({6, 1, 4}, {{2, 0, 0}, {3, 0, 0}, {1, 0, 2}, {0, 0, 1}});
  Script s(*sim);
  std::vector<std::pair<BlockId, int>> codes;
  testsupport::competeForACell(s, kTopRight, kBottomRight, codes);
  sim->runUntil(600 * kMillisecond);
  BOOST_CHECK_EQUAL(sim->world().anyAt(Cell{1, 0, 1}), 0u);
  sim->runUntilEmpty();
  const std::vector<std::pair<BlockId, int>> expected = {{0, VS_OK}, {2, VS_ERR_CELL_OCCUPIED}, {2, VS_OK}};
  BOOST_CHECK(codes == expected);
  BOOST_CHECK(sim->world().block(0).cell == (Cell{2, 0, 1}));
  BOOST_CHECK(sim->world().block(2).cell == (Cell{1, 0, 1}));
  BOOST_CHECK_EQUAL(sim->world().neighbor(2, kRight), 0u);  // the two now touch
}

BOOST_AUTO_TEST_CASE(removing_a_rolling_catom_frees_all_its_cells) {
  auto sim = makeC2D({4, 1, 3}, {{1, 0, 0}, {2, 0, 0}});
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) BOOST_CHECK_EQUAL(ctx->api->move(ctx, kTopRight), VS_OK);
  };
  sim->runUntil(kSecond / 2);
  sim->removeBlock(0);
  for (const Cell& c : {Cell{1, 0, 0}, Cell{1, 0, 1}, Cell{0, 0, 1}}) BOOST_CHECK(sim->world().isFree(c));
  sim->runUntilEmpty();
  BOOST_CHECK(s.of(0, VS_EV_MOTION_END).empty());
}

BOOST_AUTO_TEST_CASE(random_rolls_keep_the_world_consistent_and_deterministic) {
  // testsupport's random walk (each catom tries moves through random faces, a flood spreads) on a
  // crowded patch: whatever rolls succeed, every catom ends settled in its own cell, no reservation
  // is left behind, links are symmetric, and the same seed gives the same run.
  std::vector<Cell> cells;
  for (int z = 2; z < 8; ++z)
    for (int x = 2; x < 9; ++x)
      if ((x + z) % 3 != 0) cells.push_back(Cell{x, 0, z});
  testsupport::checkRandomWalk(targets::catoms2DTarget(), {11, 1, 10}, cells, 11);
}
