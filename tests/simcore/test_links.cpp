#define BOOST_TEST_MODULE simcore_links
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <vector>

#include "test_support.hpp"

using namespace simcore;
using testsupport::Rec;
using testsupport::Script;

namespace {

constexpr int kNorth = targets::kSBNorth, kEast = targets::kSBEast, kSouth = targets::kSBSouth,
              kWest = targets::kSBWest;

// Message payloads carry a sequence number in their first two bytes.
std::vector<std::uint8_t> payload(std::uint32_t size, std::uint16_t seq) {
  std::vector<std::uint8_t> p(size, 0xAB);
  if (size >= 2) {
    p[0] = std::uint8_t(seq);
    p[1] = std::uint8_t(seq >> 8);
  }
  return p;
}
std::uint16_t seqOf(const Rec& r) { return std::uint16_t(r.data[0] | (r.data[1] << 8)); }

}  // namespace

BOOST_AUTO_TEST_CASE(idle_link_arrival_is_send_time_plus_delay_plus_transmission) {
  // 100 bytes at 1 Mbit/s take 800 us; sent at t = 3 ms with a 5 us delay.
  const SimTime t0 = 3 * kMillisecond, d = 5 * kMicrosecond, tx = 800 * kMicrosecond;
  struct Case {
    SimTime latency;
    double rate;
    SimTime expected;
  };
  const Case cases[] = {{-1, -1, t0 + d + tx},
                        {20 * kMicrosecond, -1, t0 + d + tx + 20 * kMicrosecond},
                        {-1, 2e6, t0 + d + tx / 2}};
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT("latency " << c.latency << " rate " << c.rate) {
      SimulationConfig cfg;
      cfg.linkLatency = c.latency;
      cfg.linkRateBitsPerSecond = c.rate;
      auto sim = testsupport::makeSmart({4, 4, 1}, {{0, 0, 0}, {1, 0, 0}}, cfg);
      BOOST_CHECK_EQUAL(sim->link().rateBitsPerSecond, c.rate > 0 ? c.rate : 1e6);
      Script s(*sim);
      int rc = 99;
      const auto msg = payload(100, 7);
      s.onStart = [&](vs_ctx* ctx) {
        if (ctx->block == 0) ctx->api->set_timer(ctx, t0, 0, nullptr);
      };
      s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
        if (ev.kind == VS_EV_TIMER) rc = ctx->api->send(ctx, kEast, msg.data(), 100, d);
      };
      sim->runUntilEmpty();
      BOOST_CHECK_EQUAL(rc, VS_OK);
      const auto got = s.of(1, VS_EV_MESSAGE);
      BOOST_REQUIRE_EQUAL(got.size(), 1u);
      BOOST_CHECK_EQUAL(got[0].time, c.expected);
      BOOST_CHECK_EQUAL(got[0].face, kWest);
      BOOST_CHECK_EQUAL(got[0].other, 0u);
      BOOST_CHECK(got[0].data == msg);
      BOOST_CHECK_EQUAL(sim->statistics().messagesSent, 1u);
      BOOST_CHECK_EQUAL(sim->statistics().messagesReceived, 1u);
      BOOST_CHECK_EQUAL(sim->statistics().bytesSent, 100u);
    }
  }
}

BOOST_AUTO_TEST_CASE(back_to_back_sends_on_one_face_queue_fifo) {
  auto sim = testsupport::makeSmart({4, 4, 1}, {{0, 0, 0}, {1, 0, 0}});
  Script s(*sim);
  const SimTime t0 = kMillisecond;
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) ctx->api->set_timer(ctx, t0, 0, nullptr);
  };
  s.onEvent = [&](vs_ctx* ctx, const vs_event& ev) {
    if (ev.kind != VS_EV_TIMER) return;
    // Three 100-byte messages (800 us each), then a 50-byte one (400 us) handed over 5 ms later,
    // when the link is idle again, then an empty one right behind it.
    for (std::uint16_t i = 0; i < 3; ++i)
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, payload(100, i).data(), 100, 0), VS_OK);
    BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, payload(50, 3).data(), 50, 5 * kMillisecond), VS_OK);
    BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, nullptr, 0, 5 * kMillisecond), VS_OK);
  };
  sim->runUntilEmpty();
  const auto got = s.of(1, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(got.size(), 5u);
  const SimTime expected[] = {t0 + 800 * kMicrosecond, t0 + 1600 * kMicrosecond, t0 + 2400 * kMicrosecond,
                              t0 + 5 * kMillisecond + 400 * kMicrosecond,
                              t0 + 5 * kMillisecond + 400 * kMicrosecond};
  for (std::size_t i = 0; i < 5; ++i) {
    BOOST_TEST_CONTEXT("message " << i) {
      BOOST_CHECK_EQUAL(got[i].time, expected[i]);
      if (i < 4) BOOST_CHECK_EQUAL(seqOf(got[i]), i);
    }
  }
  BOOST_CHECK(got[4].data.empty());
  // The second arrives exactly one transmission time after the first.
  BOOST_CHECK_EQUAL(got[1].time - got[0].time, 800 * kMicrosecond);
}

BOOST_AUTO_TEST_CASE(sends_on_different_faces_and_directions_do_not_queue) {
  // Block 0 in the middle of a plus sign; 1 north, 2 east, 3 south, 4 west.
  auto sim = testsupport::makeSmart({3, 3, 1}, {{1, 1, 0}, {1, 2, 0}, {2, 1, 0}, {1, 0, 0}, {0, 1, 0}});
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block == 0) {
      BOOST_CHECK_EQUAL(ctx->api->send_all(ctx, payload(100, 1).data(), 100, 0), 4);
    } else if (ctx->block == 2) {
      // The reverse direction of the 0-2 link is its own FIFO.
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kWest, payload(100, 2).data(), 100, 0), VS_OK);
    }
  };
  sim->runUntilEmpty();
  const auto msgs = [&] {
    std::vector<Rec> v;
    for (const Rec& r : s.log)
      if (r.kind == VS_EV_MESSAGE) v.push_back(r);
    return v;
  }();
  BOOST_REQUIRE_EQUAL(msgs.size(), 5u);
  for (const Rec& r : msgs) BOOST_CHECK_EQUAL(r.time, 800 * kMicrosecond);
  const int backFace[] = {-1, kSouth, kWest, kNorth, kEast};
  for (BlockId b = 1; b <= 4; ++b) {
    const auto got = s.of(b, VS_EV_MESSAGE);
    BOOST_REQUIRE_EQUAL(got.size(), 1u);
    BOOST_CHECK_EQUAL(got[0].face, backFace[b]);
    BOOST_CHECK_EQUAL(got[0].other, 0u);
  }
  const auto at0 = s.of(0, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(at0.size(), 1u);
  BOOST_CHECK_EQUAL(at0[0].face, kEast);
  BOOST_CHECK_EQUAL(at0[0].other, 2u);
}

BOOST_AUTO_TEST_CASE(jitter_never_reorders_messages_of_one_link) {
  SimulationConfig cfg;
  cfg.linkJitter = kMillisecond;
  cfg.seed = 9;
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, cfg);
  BOOST_CHECK_EQUAL(sim->link().jitter, kMillisecond);
  Script s(*sim);
  constexpr std::uint16_t kCount = 400;
  const SimTime tx = 16 * kMicrosecond;  // 2 bytes at 1 Mbit/s
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block != 0) return;
    for (std::uint16_t i = 0; i < kCount; ++i) {
      BOOST_REQUIRE_EQUAL(ctx->api->send(ctx, kEast, payload(2, i).data(), 2, 0), VS_OK);
      BOOST_REQUIRE_EQUAL(ctx->api->send(ctx, kNorth, payload(2, i).data(), 2, 0), VS_OK);
    }
  };
  sim->runUntilEmpty();
  for (BlockId b : {1u, 2u}) {
    BOOST_TEST_CONTEXT("receiver " << b) {
      const auto got = s.of(b, VS_EV_MESSAGE);
      BOOST_REQUIRE_EQUAL(got.size(), kCount);
      int jittered = 0;
      for (std::uint16_t i = 0; i < kCount; ++i) {
        BOOST_REQUIRE_EQUAL(seqOf(got[i]), i);  // in sending order
        const SimTime nominal = SimTime(i + 1) * tx;
        BOOST_CHECK_GE(got[i].time, nominal);
        BOOST_CHECK_LE(got[i].time, nominal + kMillisecond);
        if (i) BOOST_CHECK_GE(got[i].time, got[i - 1].time);
        jittered += got[i].time != nominal;
      }
      BOOST_CHECK_GT(jittered, kCount / 2);  // the jitter is really applied
    }
  }
}

BOOST_AUTO_TEST_CASE(blinky_blocks_use_their_default_serial_rate) {
  const TargetSpec bb = targets::blinkyBlocksTarget();
  BOOST_CHECK_EQUAL(bb.link.rateBitsPerSecond, 38400.0);
  // Right (face 2) of block 0 touches left (face 4) of block 1.
  auto sim = testsupport::makeBlinky({2, 1, 1}, {{0, 0, 0}, {1, 0, 0}});
  BOOST_CHECK_EQUAL(sim->link().rateBitsPerSecond, 38400.0);
  Script s(*sim);
  s.onStart = [&](vs_ctx* ctx) {
    if (ctx->block != 0) return;
    BOOST_CHECK_EQUAL(ctx->api->send(ctx, targets::kBBRight, payload(6, 0).data(), 6, 0), VS_OK);  // 1.25 ms
    BOOST_CHECK_EQUAL(ctx->api->send(ctx, targets::kBBRight, payload(2, 1).data(), 2, 0),
                      VS_OK);  // +416.67 us
  };
  sim->runUntilEmpty();
  const auto got = s.of(1, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(got.size(), 2u);
  BOOST_CHECK_EQUAL(got[0].time, 1250 * kMicrosecond);
  BOOST_CHECK_EQUAL(got[0].face, targets::kBBLeft);
  // 16 bits / 38400 bit/s = 416666.67 ns, rounded to the nearest nanosecond.
  BOOST_CHECK_EQUAL(got[1].time, 1250 * kMicrosecond + 416667);
}

BOOST_AUTO_TEST_CASE(send_errors) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{0, 0, 0}, {1, 0, 0}, {2, 2, 0}});
  Script s(*sim);
  const std::vector<std::uint8_t> big(VS_MAX_MESSAGE_SIZE + 1, 1);
  s.onStart = [&](vs_ctx* ctx) {
    const std::uint8_t x = 1;
    if (ctx->block == 0) {
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kNorth, &x, 1, 0), VS_ERR_NO_NEIGHBOR);
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kWest, &x, 1, 0), VS_ERR_NO_NEIGHBOR);  // edge of the world
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, -1, &x, 1, 0), VS_ERR_BAD_FACE);
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, 4, &x, 1, 0), VS_ERR_BAD_FACE);
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, &x, 1, -1), VS_ERR_BAD_ARGUMENT);
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, nullptr, 1, 0), VS_ERR_BAD_ARGUMENT);
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, big.data(), std::uint32_t(big.size()), 0),
                        VS_ERR_TOO_LARGE);
      // The largest message is fine: 65536 bytes take 524.288 ms.
      BOOST_CHECK_EQUAL(ctx->api->send(ctx, kEast, big.data(), VS_MAX_MESSAGE_SIZE, 0), VS_OK);
    } else if (ctx->block == 2) {
      BOOST_CHECK_EQUAL(ctx->api->send_all(ctx, &x, 1, 0), 0);  // isolated: nothing queued
    }
  };
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(sim->statistics().messagesSent, 1u);
  const auto got = s.of(1, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(got.size(), 1u);
  BOOST_CHECK_EQUAL(got[0].time, 524288 * kMicrosecond);
  BOOST_CHECK_EQUAL(got[0].data.size(), std::size_t(VS_MAX_MESSAGE_SIZE));
}
