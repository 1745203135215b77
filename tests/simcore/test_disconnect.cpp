#define BOOST_TEST_MODULE simcore_disconnect
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <vector>

#include "test_support.hpp"

using namespace simcore;
using testsupport::Recorder;
using testsupport::Script;

namespace {

constexpr int kNorth = targets::kSBNorth, kEast = targets::kSBEast, kSouth = targets::kSBSouth,
              kWest = targets::kSBWest;

// Block 0 at (0,0) and block 1 at (1,0). At t = 0 block 0 queues three 1000-byte messages east
// (arrivals 8, 16, 24 ms) and block 1 one 2000-byte message west (arrival 16 ms). The link breaks
// at 10 ms: the first message of block 0 was delivered, the three others must be dropped.
void startTraffic(vs_ctx* ctx) {
  static const std::vector<std::uint8_t> data(2000, 0x5A);
  if (ctx->block == 0)
    for (int i = 0; i < 3; ++i) BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, data.data(), 1000, 0), VS_OK);
  if (ctx->block == 1) BOOST_CHECK_EQUAL(ctx->api->send(ctx, kWest, data.data(), 2000, 0), VS_OK);
}

void checkDrops(const Recorder& rec, SimTime when) {
  BOOST_REQUIRE_EQUAL(rec.drops.size(), 3u);
  int from0 = 0, from1 = 0;
  for (const auto& d : rec.drops) {
    BOOST_CHECK_EQUAL(d.when, when);
    if (d.from == 0) {
      ++from0;
      BOOST_CHECK_EQUAL(d.face, kEast);
      BOOST_CHECK_EQUAL(d.to, 1u);
    } else {
      ++from1;
      BOOST_CHECK_EQUAL(d.from, 1u);
      BOOST_CHECK_EQUAL(d.face, kWest);
      BOOST_CHECK_EQUAL(d.to, 0u);
    }
  }
  BOOST_CHECK_EQUAL(from0, 2);
  BOOST_CHECK_EQUAL(from1, 1);
}

}  // namespace

BOOST_AUTO_TEST_CASE(moving_away_drops_messages_in_flight_both_ways) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}, {1, 0, 0}});
  Recorder rec;
  sim->addObserver(&rec);
  Script s(*sim);
  int moves = 0;
  std::vector<int> sendAfterBreak;
  s.onStart = [&](vs_ctx* ctx) {
    startTraffic(ctx);
    if (ctx->block == 1) ctx->api->set_timer(ctx, 10 * kMillisecond, 1, nullptr);
    if (ctx->block == 0) ctx->api->set_timer(ctx, 20 * kMillisecond, 2, nullptr);
  };
  s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
    if (ctx->block == 1 && ev.kind == VS_EV_TIMER) BOOST_CHECK_EQUAL(ctx->api->move(ctx, kNorth), VS_OK);
    if (ctx->block == 0 && ev.kind == VS_EV_TIMER) {
      const std::uint8_t x = 0;
      sendAfterBreak.push_back(ctx->api->send(ctx, kEast, &x, 1, 0));
    }
    // Block 1 comes back south once, block 0 greets it with one message, which must get through;
    // then block 1 leaves again with nothing in flight.
    if (ctx->block == 1 && ev.kind == VS_EV_MOTION_END && ++moves == 1)
      BOOST_CHECK_EQUAL(ctx->api->move(ctx, kSouth), VS_OK);
    if (ctx->block == 0 && ev.kind == VS_EV_NEIGHBOR_ADDED) {
      const std::uint8_t hello[4] = {1, 2, 3, 4};
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, ev.face, hello, 4, 0), VS_OK);
    }
    if (ctx->block == 1 && ev.kind == VS_EV_MESSAGE && ev.size == 4)
      BOOST_CHECK_EQUAL(ctx->api->move(ctx, kNorth), VS_OK);
  };
  sim->runUntilEmpty();

  const Statistics& st = sim->statistics();
  BOOST_CHECK_EQUAL(st.messagesDropped, 3u);
  BOOST_CHECK_EQUAL(st.messagesSent, 5u);
  BOOST_CHECK_EQUAL(st.messagesReceived, 2u);
  checkDrops(rec, 10 * kMillisecond);
  BOOST_REQUIRE_EQUAL(sendAfterBreak.size(), 1u);
  BOOST_CHECK_EQUAL(sendAfterBreak[0], VS_ERR_NO_NEIGHBOR);

  const auto at1 = s.of(1, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(at1.size(), 2u);
  BOOST_CHECK_EQUAL(at1[0].time, 8 * kMillisecond);
  BOOST_CHECK_EQUAL(at1[1].data.size(), 4u);
  BOOST_CHECK(s.of(0, VS_EV_MESSAGE).empty());
  // Both sides were told at the break.
  const auto rm0 = s.of(0, VS_EV_NEIGHBOR_REMOVED), rm1 = s.of(1, VS_EV_NEIGHBOR_REMOVED);
  BOOST_REQUIRE_GE(rm0.size(), 1u);
  BOOST_REQUIRE_GE(rm1.size(), 1u);
  BOOST_CHECK_EQUAL(rm0[0].time, 10 * kMillisecond);
  BOOST_CHECK_EQUAL(rm0[0].face, kEast);
  BOOST_CHECK_EQUAL(rm0[0].other, 1u);
  BOOST_CHECK_EQUAL(rm1[0].time, 10 * kMillisecond);
  BOOST_CHECK_EQUAL(rm1[0].face, kWest);
  BOOST_CHECK_EQUAL(rm1[0].other, 0u);
}

BOOST_AUTO_TEST_CASE(removing_a_block_drops_its_messages_and_silences_it) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
  Recorder rec;
  sim->addObserver(&rec);
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    startTraffic(ctx);
    ctx->api->set_timer(ctx, 50 * kMillisecond, 0, nullptr);  // every block, block 1 included
  };
  BOOST_CHECK(sim->runUntil(10 * kMillisecond) == RunStatus::TimeLimit);
  BOOST_CHECK_EQUAL(sim->now(), 10 * kMillisecond);
  BOOST_CHECK_EQUAL(s.of(1, VS_EV_MESSAGE).size(), 1u);
  sim->removeBlock(1);
  BOOST_CHECK(!sim->world().isAlive(1));
  BOOST_CHECK(sim->world().isFree(Cell{1, 0, 0}));
  sim->removeBlock(1);  // twice is harmless
  const std::size_t logged = s.log.size();
  sim->runUntilEmpty();

  BOOST_CHECK_EQUAL(sim->statistics().messagesDropped, 3u);
  checkDrops(rec, 10 * kMillisecond);
  for (std::size_t i = logged; i < s.log.size(); ++i) BOOST_CHECK_NE(s.log[i].block, 1u);  // silenced
  BOOST_CHECK(s.of(1, VS_EV_TIMER).empty());
  BOOST_CHECK_EQUAL(s.of(0, VS_EV_TIMER).size(), 1u);
  // Both neighbors of block 1 were told, at the removal time.
  const auto rm0 = s.of(0, VS_EV_NEIGHBOR_REMOVED), rm2 = s.of(2, VS_EV_NEIGHBOR_REMOVED);
  BOOST_REQUIRE_EQUAL(rm0.size(), 1u);
  BOOST_REQUIRE_EQUAL(rm2.size(), 1u);
  BOOST_CHECK_EQUAL(rm0[0].time, 10 * kMillisecond);
  BOOST_CHECK_EQUAL(rm0[0].face, kEast);
  BOOST_CHECK_EQUAL(rm0[0].other, 1u);
  BOOST_CHECK_EQUAL(rm2[0].face, kSouth);
  BOOST_CHECK_EQUAL(rm2[0].other, 1u);
  BOOST_CHECK_EQUAL(sim->world().neighbor(0, kEast), kNoBlock);
  BOOST_CHECK_EQUAL(sim->pendingEvents(), 0u);
}

BOOST_AUTO_TEST_CASE(removing_a_moving_block_frees_both_cells) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}, {1, 0, 0}});
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 1) BOOST_CHECK_EQUAL(ctx->api->move(ctx, kNorth), VS_OK);
  };
  sim->runUntil(500 * kMillisecond);
  BOOST_CHECK(!sim->world().isFree(Cell{1, 0, 0}));
  BOOST_CHECK(!sim->world().isFree(Cell{1, 1, 0}));
  sim->removeBlock(1);
  BOOST_CHECK(sim->world().isFree(Cell{1, 0, 0}));
  BOOST_CHECK(sim->world().isFree(Cell{1, 1, 0}));
  sim->runUntilEmpty();
  BOOST_CHECK(s.of(1, VS_EV_MOTION_END).empty());
  BOOST_CHECK_EQUAL(sim->pendingEvents(), 0u);
}

BOOST_AUTO_TEST_CASE(blinky_blocks_cannot_move) {
  auto sim = testsupport::makeBlinky({3, 3, 3}, {{1, 1, 1}});
  Script s(*sim);
  int rc = 0;
  s.onStart = [&](vs_ctx* ctx) { rc = ctx->api->move(ctx, targets::kBBRight); };
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(rc, VS_ERR_UNSUPPORTED);
  BOOST_CHECK_EQUAL(sim->statistics().motionsStarted, 0u);
  BOOST_CHECK(sim->world().block(0).cell == (Cell{1, 1, 1}));
}
