#define BOOST_TEST_MODULE simcore_stability
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <sstream>
#include <vector>

#include "blinkyblocks/blinkyblocks.hpp"
#include "catoms2d/catoms2d.hpp"
#include "catoms3d/catoms3d.hpp"
#include "simcore/stability.hpp"
#include "smartblocks/smartblocks.hpp"
#include "test_support.hpp"

// The reality checker (simcore/stability.hpp) on structures worked out by hand. Blinky Blocks:
// 40 mm, 60 g (weight w = 0.5886 N), links 2.5 N, contact 40 mm wide. Catoms: 10 mm, 30 g,
// links 1.25 N, contact 5 mm. Cells are (x, y, z); a cube's centre is 40 * cell in mm.

using namespace simcore;

namespace {

constexpr double kW = 0.060 * 9.81;  // a Blinky Block's weight, N

bool near(double a, double b, double tol = 1e-9) { return std::fabs(a - b) < tol; }

StabilityReport check(const TargetSpec& target, GridSize size, const std::vector<Cell>& cells) {
  auto sim = testsupport::makeSim(target, size, cells);
  return checkStability(sim->world(), sim->target());
}

std::string text(const StabilityReport& r, const TargetSpec& t) {
  std::ostringstream o;
  printStability(o, r, t);
  return o.str();
}

}  // namespace

BOOST_AUTO_TEST_CASE(fig_6a_a_block_holding_three_on_one_side_breaks_its_link) {
  // A floor of four (#0..#3, x = 0..3), a block on the last (#4 at (3,0,1)) and three out to its
  // right (#5..#7, x = 4..6). Whole: centre of mass x = 24/8 = 3 cells, over the floor (-0.5..3.5).
  // Link #4 -> #5 holds 3 blocks whose centre is 1.5 cells right of the contact (x = 3.5):
  // F = 3w (1 sheared + 1.5 moment) = 7.5 w = 4.41 N > 2.5 N. #5 -> #6: 2w (1 + 1) = 2.35 N;
  // #3 -> #4 (resting): 4 blocks, centre 1.5 cells = 60 mm off, F = 4w (60 - 20) / 40 = 2.35 N.
  const TargetSpec t = targets::blinkyBlocksTarget();
  const auto r = check(t, {7, 1, 2}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {3, 0, 1}, {4, 0, 1}, {5, 0, 1}, {6, 0, 1}});
  BOOST_CHECK(!r.stable());
  BOOST_CHECK(r.tipping.empty() && r.falling.empty());
  BOOST_REQUIRE_EQUAL(r.overloaded.size(), 1u);
  const OverloadedLink& o = r.overloaded[0];
  BOOST_CHECK_EQUAL(o.carrier, 4u);
  BOOST_CHECK_EQUAL(o.held, 5u);
  BOOST_CHECK_EQUAL(o.face, targets::kBBRight);
  BOOST_CHECK(near(o.hanging, 3));
  BOOST_CHECK(near(o.forceN, 7.5 * kW));
  BOOST_CHECK(near(r.maxLinkForceN, 7.5 * kW));
  BOOST_CHECK_EQUAL(r.loadedLinks, 4u);
  BOOST_CHECK_EQUAL(text(r, t),
                    "stability: unstable (1 link overloaded; largest link force 4.41 N of 2.50 N)\n"
                    "  link #4 right -> #5: must carry 4.41 N, holds 2.50 N (3 blocks' weight on it)\n");
}

BOOST_AUTO_TEST_CASE(a_block_holds_two_on_one_side) {
  // The same with two out: #4 -> #5 carries 2w (1 + 1) = 2.35 N; #3 -> #4: 3 blocks, centre
  // 1 cell = 40 mm off, 3w (40 - 20) / 40 = 0.88 N.
  const TargetSpec t = targets::blinkyBlocksTarget();
  const auto r = check(t, {7, 1, 2}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {3, 0, 1}, {4, 0, 1}, {5, 0, 1}});
  BOOST_CHECK(r.stable());
  BOOST_CHECK(near(r.maxLinkForceN, 4 * kW));
  BOOST_CHECK_EQUAL(text(r, t),
                    "stability: stable (1 structure of 7 blocks, 3 loaded links; largest link force 2.35 N of 2.50 N)\n");
}

BOOST_AUTO_TEST_CASE(fig_6b_a_structure_tips_about_a_floor_edge) {
  // One floor block #0, #1 on it, #2 and #3 out to the right at z = 1: centre of mass x = 3/4 cell =
  // 30 mm, z = 30 mm, beyond the floor block's right edge x = 20 mm: it tips about that edge.
  const TargetSpec t = targets::blinkyBlocksTarget();
  const auto r = check(t, {4, 1, 2}, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {2, 0, 1}});
  BOOST_REQUIRE_EQUAL(r.tipping.size(), 1u);
  const TippingStructure& s = r.tipping[0];
  BOOST_CHECK((s.blocks == std::vector<BlockId>{0, 1, 2, 3}));
  BOOST_CHECK(near(s.centreOfMassMm.x, 30) && near(s.centreOfMassMm.y, 0) && near(s.centreOfMassMm.z, 30));
  BOOST_CHECK(near(s.pivotFromMm.x, 20) && near(s.pivotFromMm.y, -20));
  BOOST_CHECK(near(s.pivotToMm.x, 20) && near(s.pivotToMm.y, 20));
  BOOST_CHECK((s.pivotBlocks == std::vector<BlockId>{0}));
  BOOST_CHECK(r.overloaded.empty());  // #1 -> #2 holds 2w (1 + 1) = 2.35 N
  BOOST_CHECK_EQUAL(text(r, t),
                    "stability: unstable (1 structure tips over; largest link force 2.35 N of 2.50 N)\n"
                    "  structure #0 #1 #2 #3: centre of mass (30.0, 0.0, 30.0) mm outside its floor contacts; it "
                    "tips about the axis (20.0, -20.0) - (20.0, 20.0) mm of floor block #0\n");
}

BOOST_AUTO_TEST_CASE(a_block_hanging_below_an_arm_pulls_and_the_arm_breaks) {
  // Floor #0..#2 (x = 0..2), column #3, #4 at x = 2 (z = 1, 2), arm #5, #6 at z = 2 (x = 3, 4) and
  // #7 hanging under #6 at (4,0,1). #6 -> #7 pulls out w (the link below carries it, no moment).
  // #4 -> #5 holds #5 #6 #7, centre x = 11/3, 7/6 cell from the contact (2.5): 3w (1 + 7/6) = 3.83 N.
  // Whole: x = 18/8 = 2.25 cells, over the floor (-0.5..2.5).
  const TargetSpec t = targets::blinkyBlocksTarget();
  const auto r = check(t, {5, 1, 3},
                       {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 1}, {2, 0, 2}, {3, 0, 2}, {4, 0, 2}, {4, 0, 1}});
  BOOST_CHECK(r.tipping.empty());
  BOOST_REQUIRE_EQUAL(r.overloaded.size(), 1u);
  BOOST_CHECK_EQUAL(r.overloaded[0].carrier, 4u);
  BOOST_CHECK_EQUAL(r.overloaded[0].held, 5u);
  BOOST_CHECK(near(r.overloaded[0].forceN, 3 * kW * (1 + 7.0 / 6)));
  BOOST_CHECK(near(r.maxLinkForceN, 3 * kW * (1 + 7.0 / 6)));
}

BOOST_AUTO_TEST_CASE(a_structure_off_the_floor_falls) {
  // Two blocks on the floor and a separate pair at z = 2 and 3.
  const TargetSpec t = targets::blinkyBlocksTarget();
  const auto r = check(t, {3, 3, 4}, {{0, 0, 0}, {1, 0, 0}, {2, 2, 2}, {2, 2, 3}});
  BOOST_CHECK_EQUAL(r.structures, 2u);
  BOOST_REQUIRE_EQUAL(r.falling.size(), 1u);
  BOOST_CHECK((r.falling[0].blocks == std::vector<BlockId>{2, 3}));
  BOOST_CHECK(text(r, t).find("  structure #2 #3: no block on the floor, it falls\n") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(catoms_3d_a_ball_on_a_ball_rolls_off_one_in_a_hollow_stays) {
  const TargetSpec t = targets::catoms3DTarget();
  // (2,2,1) sits over the hollow of (2,2,0), (3,2,0), (2,3,0), (3,3,0): its centre (25, 25) mm is
  // the centre of their contact points.
  const auto hollow = check(t, {5, 5, 2}, {{2, 2, 0}, {3, 2, 0}, {2, 3, 0}, {3, 3, 0}, {2, 2, 1}});
  BOOST_CHECK(hollow.stable());
  // Over one catom only: the centre of mass (22.5, 22.5) mm is off its one contact point (20, 20):
  // it tips about that point.
  const auto single = check(t, {5, 5, 2}, {{2, 2, 0}, {2, 2, 1}});
  BOOST_REQUIRE_EQUAL(single.tipping.size(), 1u);
  const TippingStructure& s = single.tipping[0];
  BOOST_CHECK(near(s.centreOfMassMm.x, 22.5) && near(s.centreOfMassMm.y, 22.5));
  BOOST_CHECK(near(s.pivotFromMm.x, 20) && near(s.pivotToMm.x, 20) && near(s.pivotFromMm.y, 20));
  BOOST_CHECK(text(single, t).find("tips about the corner (20.0, 20.0) mm of floor block #0") != std::string::npos);
  // On a row of two, over the line between their contacts: on the hull's edge, which holds.
  const auto row = check(t, {5, 5, 2}, {{1, 2, 0}, {2, 2, 0}, {3, 2, 0}, {1, 2, 1}});
  BOOST_REQUIRE_EQUAL(row.tipping.size(), 1u);  // (1,2,1) is at y = 2.5: off the row's line y = 2
  BOOST_CHECK(near(row.tipping[0].pivotFromMm.y, 20) && near(row.tipping[0].pivotToMm.y, 20));
}

BOOST_AUTO_TEST_CASE(catoms_3d_links_hold_one_catom_out_not_two) {
  // A floor of two rows (#0..#3 at y = 2, #4..#7 at y = 3, x = 0..3) and an arm in the odd layer:
  // #8 (3,2,1) rests on #3 and #7 (half its load each), #9 (4,2,1) and #10 (5,2,1) have nothing
  // below (centres x = 4.5, 5.5 cells): #8 holds both sideways, their centre 1 diameter from the
  // contact (x = 4): F = 2 w (1 + 10/5) = 6 w = 1.77 N > 1.25 N; #9 -> #10: w (1 + 5/5) = 0.59 N.
  // Whole: centre x = 25.5/11 = 2.3 cells, over the floor (0..3).
  const TargetSpec t = targets::catoms3DTarget();
  const double wc = 0.030 * 9.81;
  const auto r = check(t, {7, 5, 2},
                       {{0, 2, 0}, {1, 2, 0}, {2, 2, 0}, {3, 2, 0}, {0, 3, 0}, {1, 3, 0}, {2, 3, 0}, {3, 3, 0},
                        {3, 2, 1}, {4, 2, 1}, {5, 2, 1}});
  BOOST_CHECK(r.tipping.empty());
  BOOST_REQUIRE_EQUAL(r.overloaded.size(), 1u);
  BOOST_CHECK_EQUAL(r.overloaded[0].carrier, 8u);
  BOOST_CHECK_EQUAL(r.overloaded[0].held, 9u);
  BOOST_CHECK_EQUAL(r.overloaded[0].face, targets::kC3DSide0);
  BOOST_CHECK(near(r.overloaded[0].forceN, 6 * wc));
  // Without #10 the arm holds: 2 w = 0.59 N.
  const auto shorter = check(t, {7, 5, 2},
                             {{0, 2, 0}, {1, 2, 0}, {2, 2, 0}, {3, 2, 0}, {0, 3, 0}, {1, 3, 0}, {2, 3, 0}, {3, 3, 0},
                              {3, 2, 1}, {4, 2, 1}});
  BOOST_CHECK(shorter.overloaded.empty());
}

BOOST_AUTO_TEST_CASE(smart_blocks_have_nothing_to_check) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}});
  BOOST_CHECK_THROW(checkStability(sim->world(), sim->target()), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(the_guard_reports_or_refuses_a_motion_that_would_tip_the_structure) {
  // Catoms 2D (x-z plane; odd rows shifted by half a cell): floor #0 (0,0,0), #1 (1,0,0); #2
  // (0,0,1) and #3 (1,0,1) above them (x = 0.5, 1.5); #4 on top at (1,0,2) (x = 1). #4 rolls right
  // to (2,0,2) (x = 2: the centre of mass reaches x = 5/5 = 1, the floor's end, and holds), then
  // down-right to (2,0,1) (x = 2.5: centre of mass 5.5/5 = 1.1 > 1, it would tip about #1).
  for (const bool refuse : {false, true}) {
    BOOST_TEST_CONTEXT("refuse " << refuse) {
      auto sim = testsupport::makeSim(targets::catoms2DTarget(), {5, 1, 4},
                                      {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 2}});
      std::ostringstream log;
      StabilityGuard guard(&log, refuse);
      sim->setMotionCheck(&guard);
      testsupport::Script s(*sim);
      std::vector<int> codes;
      s.onStart = [&](vs_ctx* ctx) {
        if (ctx->block == 4) codes.push_back(ctx->api->move(ctx, targets::kC2DRight));
      };
      s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
        if (ctx->block == 4 && ev.kind == VS_EV_MOTION_END && codes.size() == 1)
          codes.push_back(ctx->api->move(ctx, targets::kC2DBottomRight));
      };
      sim->runUntilEmpty();
      BOOST_CHECK_EQUAL(guard.checked(), 2u);
      BOOST_CHECK_EQUAL(guard.unstable(), 1u);
      BOOST_CHECK((codes == std::vector<int>{VS_OK, refuse ? VS_ERR_UNSTABLE : VS_OK}));
      BOOST_CHECK(sim->world().block(4).cell == (refuse ? Cell{2, 0, 2} : Cell{2, 0, 1}));
      BOOST_CHECK(log.str().find("block #4 moving to (2,0,1): stability: unstable (1 structure tips over") !=
                  std::string::npos);
      BOOST_CHECK(log.str().find("tips about the corner (10.0, 0.0) mm of floor block #1") != std::string::npos);
      BOOST_CHECK_EQUAL(checkStability(sim->world(), sim->target()).stable(), refuse);
    }
  }
}
