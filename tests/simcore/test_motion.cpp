#define BOOST_TEST_MODULE simcore_motion
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "test_support.hpp"

using namespace simcore;
using testsupport::Rec;
using testsupport::Recorder;
using testsupport::Script;

namespace {

constexpr int kNorth = targets::kSBNorth, kEast = targets::kSBEast, kSouth = targets::kSBSouth,
              kWest = targets::kSBWest;

bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }

}  // namespace

BOOST_AUTO_TEST_CASE(destination_is_reserved_at_motion_start) {
  // Blocks 0 and 1 both want the cell (1,1) between them at t = 0: block 0 starts first and wins.
  auto sim = testsupport::makeSmart({5, 5, 1}, {{0, 1, 0}, {2, 1, 0}});
  Script s(*sim);
  std::vector<int> rc(2, 99);
  s.onStart = [&](vs_ctx* ctx) { rc[ctx->block] = ctx->api->move(ctx, ctx->block == 0 ? kEast : kWest); };
  sim->runUntil(kMillisecond);
  BOOST_CHECK_EQUAL(rc[0], VS_OK);
  BOOST_CHECK_EQUAL(rc[1], VS_ERR_CELL_OCCUPIED);
  BOOST_CHECK(!sim->world().isFree(Cell{1, 1, 0}));
  BOOST_CHECK_EQUAL(sim->world().anyAt(Cell{1, 1, 0}), 0u);
  BOOST_CHECK_EQUAL(sim->world().settledAt(Cell{1, 1, 0}), kNoBlock);  // reserved, not settled
  sim->runUntilEmpty();
  BOOST_CHECK(sim->world().block(0).cell == (Cell{1, 1, 0}));
  BOOST_CHECK(sim->world().block(1).cell == (Cell{2, 1, 0}));
  BOOST_CHECK_EQUAL(sim->statistics().motionsStarted, 1u);
  BOOST_CHECK_EQUAL(sim->statistics().motionsEnded, 1u);
  // The two are now attached: east of 0 is 1.
  const auto add0 = s.of(0, VS_EV_NEIGHBOR_ADDED), add1 = s.of(1, VS_EV_NEIGHBOR_ADDED);
  BOOST_REQUIRE_EQUAL(add0.size(), 1u);
  BOOST_REQUIRE_EQUAL(add1.size(), 1u);
  BOOST_CHECK_EQUAL(add0[0].face, kEast);
  BOOST_CHECK_EQUAL(add0[0].other, 1u);
  BOOST_CHECK_EQUAL(add1[0].face, kWest);
  BOOST_CHECK_EQUAL(add1[0].other, 0u);
  BOOST_CHECK_EQUAL(add0[0].time, kSecond);
}

BOOST_AUTO_TEST_CASE(move_errors_busy_out_of_world_bad_face_occupied) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}, {2, 2, 0}, {1, 2, 0}});
  Script s(*sim);
  std::vector<int> codes;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) {
      codes.push_back(ctx->api->move(ctx, kWest));   // out of world
      codes.push_back(ctx->api->move(ctx, kSouth));  // out of world
      codes.push_back(ctx->api->move(ctx, 4));       // bad face
      codes.push_back(ctx->api->move(ctx, -1));      // bad face
      codes.push_back(ctx->api->move(ctx, kEast));   // ok
      codes.push_back(ctx->api->move(ctx, kNorth));  // busy
      ctx->api->set_timer(ctx, 500 * kMillisecond, 0, nullptr);
    } else if (ctx->block == 1) {
      codes.push_back(ctx->api->move(ctx, kNorth));  // out of world
      codes.push_back(ctx->api->move(ctx, kWest));   // settled neighbor there
    }
  };
  s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
    if (ev.kind == VS_EV_TIMER) codes.push_back(ctx->api->move(ctx, kNorth));       // still busy mid-motion
    if (ev.kind == VS_EV_MOTION_END) codes.push_back(ctx->api->move(ctx, kNorth));  // free again
  };
  sim->runUntilEmpty();
  // Block 0: (0,0) -> (1,0) at 1 s -> (1,1) at 2 s, then (1,2) is block 2's cell.
  const std::vector<int> expected = {
      VS_ERR_OUT_OF_WORLD, VS_ERR_OUT_OF_WORLD, VS_ERR_BAD_FACE,      VS_ERR_BAD_FACE, VS_OK,
      VS_ERR_BUSY,         VS_ERR_OUT_OF_WORLD, VS_ERR_CELL_OCCUPIED, VS_ERR_BUSY,     VS_OK,
      VS_ERR_CELL_OCCUPIED};
  BOOST_CHECK_EQUAL_COLLECTIONS(codes.begin(), codes.end(), expected.begin(), expected.end());
  BOOST_CHECK(sim->world().block(0).cell == (Cell{1, 1, 0}));
  BOOST_CHECK_EQUAL(sim->world().neighbor(0, kNorth), 2u);
  BOOST_CHECK_EQUAL(sim->statistics().motionsStarted, 2u);
  BOOST_CHECK_EQUAL(sim->now(), 2 * kSecond);
}

BOOST_AUTO_TEST_CASE(neighbors_removed_at_start_and_added_at_end_on_both_sides) {
  // A = 0 at (1,1), B = 1 east of it, C = 2 at (1,3). A moves north at 100 ms: it leaves B and, one
  // second later, reaches C.
  auto sim = testsupport::makeSmart({5, 5, 1}, {{1, 1, 0}, {2, 1, 0}, {1, 3, 0}});
  Script s(*sim);
  const SimTime t0 = 100 * kMillisecond;
  std::vector<int> counts;
  std::vector<std::int32_t> pos;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) ctx->api->set_timer(ctx, t0, 0, nullptr);
  };
  s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
    if (ctx->block == 0 && ev.kind == VS_EV_TIMER) {
      BOOST_CHECK_EQUAL(ctx->api->neighbor_count(ctx), 1);
      BOOST_CHECK_EQUAL(ctx->api->move(ctx, kNorth), VS_OK);
      // While moving, a block has no neighbors, and the position service gives the destination.
      BOOST_CHECK_EQUAL(ctx->api->neighbor_count(ctx), 0);
      BOOST_CHECK_EQUAL(ctx->api->neighbor(ctx, kEast), VS_NO_BLOCK);
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, "m", 1, 0), VS_ERR_NO_NEIGHBOR);
      std::int32_t xyz[3];
      ctx->api->position(ctx, xyz);
      pos.assign(xyz, xyz + 3);
    }
    if (ctx->block == 1 && ev.kind == VS_EV_NEIGHBOR_REMOVED) {
      BOOST_CHECK_EQUAL(ctx->api->neighbor(ctx, kWest), VS_NO_BLOCK);
      counts.push_back(ctx->api->neighbor_count(ctx));
    }
  };
  sim->runUntilEmpty();
  BOOST_CHECK((pos == std::vector<std::int32_t>{1, 2, 0}));
  BOOST_CHECK((counts == std::vector<int>{0}));
  std::vector<Rec> notes;  // neighbor and motion events, in processing order
  for (const Rec& r : s.log)
    if (r.kind == VS_EV_NEIGHBOR_ADDED || r.kind == VS_EV_NEIGHBOR_REMOVED || r.kind == VS_EV_MOTION_END)
      notes.push_back(r);
  BOOST_REQUIRE_EQUAL(notes.size(), 5u);
  struct Expect {
    SimTime t;
    BlockId block;
    int kind, face;
    BlockId other;
  };
  const Expect expected[] = {{t0, 0, VS_EV_NEIGHBOR_REMOVED, kEast, 1},
                             {t0, 1, VS_EV_NEIGHBOR_REMOVED, kWest, 0},
                             {t0 + kSecond, 0, VS_EV_MOTION_END, -1, VS_NO_BLOCK},
                             {t0 + kSecond, 0, VS_EV_NEIGHBOR_ADDED, kNorth, 2},
                             {t0 + kSecond, 2, VS_EV_NEIGHBOR_ADDED, kSouth, 0}};
  for (std::size_t i = 0; i < 5; ++i) {
    BOOST_TEST_CONTEXT("notification " << i) {
      BOOST_CHECK_EQUAL(notes[i].time, expected[i].t);
      BOOST_CHECK_EQUAL(notes[i].block, expected[i].block);
      BOOST_CHECK_EQUAL(notes[i].kind, expected[i].kind);
      BOOST_CHECK_EQUAL(notes[i].face, expected[i].face);
      BOOST_CHECK_EQUAL(notes[i].other, expected[i].other);
    }
  }
}

BOOST_AUTO_TEST_CASE(position_interpolates_mid_motion) {
  for (SimTime duration : {SimTime(-1), 2 * kSecond}) {
    BOOST_TEST_CONTEXT("motion duration " << duration) {
      SimulationConfig cfg;
      cfg.motionDuration = duration;
      const SimTime d = duration > 0 ? duration : kSecond;
      auto sim = testsupport::makeSmart({5, 5, 1}, {{1, 1, 0}, {3, 3, 0}}, cfg);
      struct Started : Recorder {
        std::vector<std::pair<Cell, Cell>> moves;
        std::vector<SimTime> ends;
        void onMotionStarted(const Simulation&, std::uint32_t, const Cell& from, const Cell& to,
                             SimTime end) override {
          moves.emplace_back(from, to);
          ends.push_back(end);
        }
      } obs;
      sim->addObserver(&obs);
      Script s(*sim);
      const SimTime t0 = 100 * kMillisecond;
      s.onStart = [&](vs_ctx* ctx) {
        if (ctx->block == 0) ctx->api->set_timer(ctx, t0, 0, nullptr);
      };
      s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
        if (ev.kind == VS_EV_TIMER) BOOST_CHECK_EQUAL(ctx->api->move(ctx, kEast), VS_OK);
      };
      sim->runUntil(t0 + d / 4);
      Vec3 p = sim->position(0);
      BOOST_CHECK(near(p.x, 1.25) && near(p.y, 1.0) && near(p.z, 0.0));
      sim->runUntil(t0 + d / 2);
      p = sim->position(0);
      BOOST_CHECK_MESSAGE(near(p.x, 1.5) && near(p.y, 1.0), "half way: " << p.x << ", " << p.y);
      p = sim->position(1);
      BOOST_CHECK(near(p.x, 3.0) && near(p.y, 3.0));  // the other block stays put
      sim->runUntilEmpty();
      p = sim->position(0);
      BOOST_CHECK(near(p.x, 2.0) && near(p.y, 1.0));
      const auto ends = s.of(0, VS_EV_MOTION_END);
      BOOST_REQUIRE_EQUAL(ends.size(), 1u);
      BOOST_CHECK_EQUAL(ends[0].time, t0 + d);
      BOOST_REQUIRE_EQUAL(obs.moves.size(), 1u);
      BOOST_CHECK(obs.moves[0].first == (Cell{1, 1, 0}));
      BOOST_CHECK(obs.moves[0].second == (Cell{2, 1, 0}));
      BOOST_CHECK_EQUAL(obs.ends[0], t0 + d);
    }
  }
}

BOOST_AUTO_TEST_CASE(origin_cell_cannot_be_entered_while_the_mover_leaves) {
  // A = 0 at (1,1) moves east at 1 ms; D = 1 at (0,1) and E = 2 at (1,2) try to enter (1,1) at
  // 0.5 s (refused), D again at 1.5 s (after A's motion ended: allowed).
  auto sim = testsupport::makeSmart({4, 4, 1}, {{1, 1, 0}, {0, 1, 0}, {1, 2, 0}});
  Script s(*sim);
  std::vector<std::pair<BlockId, int>> codes;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) ctx->api->set_timer(ctx, kMillisecond, 0, nullptr);
    if (ctx->block == 1) {
      ctx->api->set_timer(ctx, 500 * kMillisecond, 0, nullptr);
      ctx->api->set_timer(ctx, 1500 * kMillisecond, 0, nullptr);
    }
    if (ctx->block == 2) ctx->api->set_timer(ctx, 500 * kMillisecond, 0, nullptr);
  };
  s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
    if (ev.kind != VS_EV_TIMER) return;
    const int face = ctx->block == 0 ? kEast : ctx->block == 1 ? kEast : kSouth;
    codes.emplace_back(ctx->block, ctx->api->move(ctx, face));
  };
  sim->runUntil(600 * kMillisecond);
  BOOST_CHECK(!sim->world().isFree(Cell{1, 1, 0}));
  BOOST_CHECK_EQUAL(sim->world().anyAt(Cell{1, 1, 0}), 0u);
  BOOST_CHECK_EQUAL(sim->world().settledAt(Cell{2, 1, 0}), kNoBlock);
  sim->runUntilEmpty();
  const std::vector<std::pair<BlockId, int>> expected = {
      {0, VS_OK}, {1, VS_ERR_CELL_OCCUPIED}, {2, VS_ERR_CELL_OCCUPIED}, {1, VS_OK}};
  BOOST_REQUIRE_EQUAL(codes.size(), expected.size());
  for (std::size_t i = 0; i < codes.size(); ++i) {
    BOOST_CHECK_EQUAL(codes[i].first, expected[i].first);
    BOOST_CHECK_EQUAL(codes[i].second, expected[i].second);
  }
  BOOST_CHECK(sim->world().block(0).cell == (Cell{2, 1, 0}));
  BOOST_CHECK(sim->world().block(1).cell == (Cell{1, 1, 0}));
  BOOST_CHECK_EQUAL(sim->world().settledAt(Cell{1, 1, 0}), 1u);
  BOOST_CHECK(sim->world().isFree(Cell{0, 1, 0}));
}
