#define BOOST_TEST_MODULE simcore_blockcode_abi
#include <dlfcn.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "simcore/rng.hpp"
#include "test_support.hpp"

using namespace simcore;
using testsupport::Rec;
using testsupport::Recorder;
using testsupport::Script;

namespace {

constexpr int kRight = targets::kBBRight, kLeft = targets::kBBLeft, kTop = targets::kBBTop,
              kBottom = targets::kBBBottom;

// Per-block state of the recording program: odd-sized on purpose (the host rounds it up).
struct AbiState {
  std::uint32_t marker;
  std::uint8_t bytes[19];
};
static_assert(sizeof(AbiState) == 24);

bool allZero(const void* p, std::size_t n) {
  const auto* b = static_cast<const std::uint8_t*>(p);
  for (std::size_t i = 0; i < n; ++i)
    if (b[i]) return false;
  return true;
}

struct Library {
  void* handle = nullptr;
  ~Library() {
    if (handle) dlclose(handle);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(every_host_service_round_trips_through_the_c_table) {
  // Blinky Blocks: 0 at the origin, 1 to its right, 2 on top of it.
  SimulationConfig cfg;
  cfg.seed = 1234;
  auto sim = testsupport::makeBlinky({2, 1, 2}, {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, cfg);
  Recorder rec;
  sim->addObserver(&rec);
  Script s(*sim, sizeof(AbiState));
  std::uint64_t id1 = 0, id2 = 0;
  std::vector<std::uintptr_t> states;
  std::vector<std::uint32_t> drawn;
  s.onStart = [&](vs_ctx* c) {
    const vs_host_api* api = c->api;
    BOOST_CHECK_EQUAL(api->abi_version, std::uint32_t(VS_ABI_VERSION));
    BOOST_REQUIRE(c->state != nullptr);
    BOOST_CHECK(allZero(c->state, sizeof(AbiState)));  // zeroed before start
    BOOST_CHECK_EQUAL(reinterpret_cast<std::uintptr_t>(c->state) % 16, 0u);
    BOOST_CHECK_EQUAL(c->state, sim->blockState(c->block));
    states.push_back(reinterpret_cast<std::uintptr_t>(c->state));
    static_cast<AbiState*>(c->state)->marker = 1000 + c->block;
    std::memset(static_cast<AbiState*>(c->state)->bytes, 0xEE, sizeof AbiState::bytes);  // fill it all
    BOOST_CHECK_EQUAL(api->now(c), 0);
    BOOST_CHECK_EQUAL(api->face_count(c), 6);
    BOOST_CHECK_EQUAL(api->block_count(c), 3u);
    if (c->block != 0) return;

    BOOST_CHECK_EQUAL(api->neighbor_count(c), 2);
    BOOST_CHECK_EQUAL(api->neighbor(c, kRight), 1u);
    BOOST_CHECK_EQUAL(api->neighbor(c, kTop), 2u);
    BOOST_CHECK_EQUAL(api->neighbor(c, kBottom), VS_NO_BLOCK);
    BOOST_CHECK_EQUAL(api->neighbor(c, 6), VS_NO_BLOCK);
    BOOST_CHECK_EQUAL(api->neighbor(c, -1), VS_NO_BLOCK);
    std::int32_t xyz[3] = {9, 9, 9};
    api->position(c, xyz);
    BOOST_CHECK(xyz[0] == 0 && xyz[1] == 0 && xyz[2] == 0);

    BOOST_CHECK_EQUAL(api->color(c), 0x808080u);  // Blinky Blocks default
    BOOST_CHECK_EQUAL(api->set_color(c, 0x123456), VS_OK);
    BOOST_CHECK_EQUAL(api->color(c), 0x123456u);
    BOOST_CHECK_EQUAL(api->set_color(c, 0xFF00FF00u), VS_OK);
    BOOST_CHECK_EQUAL(api->color(c), 0x00FF00u);                  // only 0xRRGGBB is kept
    BOOST_CHECK_EQUAL(api->set_value(c, 5), VS_ERR_UNSUPPORTED);  // no display on Blinky Blocks

    std::int32_t acc[3] = {7, 7, 7};
    BOOST_CHECK_EQUAL(api->read_sensor(c, VS_SENSOR_ACCEL, acc), VS_OK);
    BOOST_CHECK(acc[0] == 0 && acc[1] == 0 && acc[2] == -1);  // at rest
    BOOST_CHECK_EQUAL(api->read_sensor(c, 99, acc), VS_ERR_UNSUPPORTED);

    BOOST_CHECK_EQUAL(api->send(c, kRight, "hello", 5, 0), VS_OK);
    BOOST_CHECK_EQUAL(api->send_all(c, "x", 1, 0), 2);

    BOOST_CHECK_EQUAL(api->set_timer(c, kMillisecond, 7, &id1), VS_OK);
    BOOST_CHECK_EQUAL(api->set_timer(c, 2 * kMillisecond, 8, &id2), VS_OK);
    BOOST_CHECK_NE(id1, id2);
    BOOST_CHECK_EQUAL(api->cancel_timer(c, id2), VS_OK);
    BOOST_CHECK_EQUAL(api->cancel_timer(c, id2), VS_ERR_NOT_FOUND);
    BOOST_CHECK_EQUAL(api->cancel_timer(c, 0xDEAD0000BEEFull), VS_ERR_NOT_FOUND);
    BOOST_CHECK_EQUAL(api->set_timer(c, -1, 0, nullptr), VS_ERR_BAD_ARGUMENT);
    BOOST_CHECK_EQUAL(api->set_timer(c, 3 * kMillisecond, 9, nullptr), VS_OK);

    for (int i = 0; i < 3; ++i) drawn.push_back(api->random_u32(c));
    BOOST_CHECK_LT(api->random_below(c, 10), 10u);
    api->trace(c, "hello trace");
    api->trace(c, nullptr);  // ignored
  };
  s.onEvent = [&](vs_ctx* c, const vs_event& ev) {
    BOOST_CHECK_EQUAL(static_cast<AbiState*>(c->state)->marker, 1000 + c->block);  // kept, per block
    if (ev.kind == VS_EV_TIMER && ev.tag == 7)
      BOOST_CHECK_EQUAL(c->api->cancel_timer(c, id1), VS_ERR_NOT_FOUND);
    if (ev.kind == VS_EV_SENSOR) {
      std::int32_t acc[3] = {0, 0, 0};
      BOOST_CHECK_EQUAL(c->api->read_sensor(c, VS_SENSOR_ACCEL, acc), VS_OK);
      BOOST_CHECK(acc[0] == 1 && acc[1] == 2 && acc[2] == 3);  // the latest reading
    }
    if (ev.kind == VS_EV_TAP) {
      std::int32_t acc[3] = {0, 0, 0};
      c->api->read_sensor(c, VS_SENSOR_ACCEL, acc);
      BOOST_CHECK(acc[0] == 0 && acc[1] == 0 && acc[2] == -1);  // block 1 was never shaken
    }
  };
  sim->scheduleTap(1, 5 * kMillisecond);
  sim->scheduleAccel(2, 6 * kMillisecond, 1, 2, 3);
  sim->runUntilEmpty();

  BOOST_CHECK_EQUAL(s.count(testsupport::kStartRec), 3u);
  BOOST_REQUIRE_EQUAL(states.size(), 3u);
  BOOST_CHECK(states[0] != states[1] && states[1] != states[2] && states[0] != states[2]);
  std::uint64_t st = BlockRng::initialState(1234, 0);
  for (std::uint32_t v : drawn) BOOST_CHECK_EQUAL(v, BlockRng::next(st, 0));
  BOOST_CHECK_EQUAL(sim->world().block(0).color, 0x00FF00u);
  BOOST_CHECK_EQUAL(rec.colors.size(), 2u);
  BOOST_REQUIRE_EQUAL(rec.traces.size(), 1u);
  BOOST_CHECK_EQUAL(rec.traces[0].first, 0u);
  BOOST_CHECK_EQUAL(rec.traces[0].second, "hello trace");

  // Messages: "hello" then "x" on block 1's left face, "x" on block 2's bottom face.
  const auto m1 = s.of(1, VS_EV_MESSAGE), m2 = s.of(2, VS_EV_MESSAGE);
  BOOST_REQUIRE_EQUAL(m1.size(), 2u);
  BOOST_REQUIRE_EQUAL(m2.size(), 1u);
  BOOST_CHECK_EQUAL(std::string(m1[0].data.begin(), m1[0].data.end()), "hello");
  BOOST_CHECK_EQUAL(m1[0].face, kLeft);
  BOOST_CHECK_EQUAL(m1[0].other, 0u);
  BOOST_CHECK_EQUAL(std::string(m1[1].data.begin(), m1[1].data.end()), "x");
  BOOST_CHECK_EQUAL(m2[0].face, kBottom);
  BOOST_CHECK_EQUAL(m2[0].other, 0u);
  BOOST_CHECK_EQUAL(m2[0].time, 208333);  // 8 bits at 38.4 kbit/s
  // Timers: tag 7 at 1 ms with its id, tag 9 at 3 ms, the cancelled tag 8 never.
  const auto timers = s.of(0, VS_EV_TIMER);
  BOOST_REQUIRE_EQUAL(timers.size(), 2u);
  BOOST_CHECK_EQUAL(timers[0].tag, 7u);
  BOOST_CHECK_EQUAL(timers[0].timerId, id1);
  BOOST_CHECK_EQUAL(timers[0].time, kMillisecond);
  BOOST_CHECK_EQUAL(timers[0].face, -1);
  BOOST_CHECK_EQUAL(timers[0].other, VS_NO_BLOCK);
  BOOST_CHECK_EQUAL(timers[1].tag, 9u);
  BOOST_CHECK_EQUAL(timers[1].timerId, 0u);  // set without asking for an id
  BOOST_CHECK_EQUAL(timers[1].time, 3 * kMillisecond);
  BOOST_CHECK_EQUAL(sim->statistics().timersCancelled, 1u);
  // Tap and sensor reading.
  const auto taps = s.of(1, VS_EV_TAP);
  BOOST_REQUIRE_EQUAL(taps.size(), 1u);
  BOOST_CHECK_EQUAL(taps[0].time, 5 * kMillisecond);
  const auto sensors = s.of(2, VS_EV_SENSOR);
  BOOST_REQUIRE_EQUAL(sensors.size(), 1u);
  BOOST_CHECK_EQUAL(sensors[0].time, 6 * kMillisecond);
  BOOST_CHECK_EQUAL(sensors[0].sensor, VS_SENSOR_ACCEL);
  BOOST_CHECK(sensors[0].values[0] == 1 && sensors[0].values[1] == 2 && sensors[0].values[2] == 3);
  BOOST_CHECK_EQUAL(s.log.size(), 3u + 3u + 2u + 1u + 1u);  // starts, messages, timers, tap, sensor
}

BOOST_AUTO_TEST_CASE(smart_blocks_services_value_and_sensor) {
  auto sim = testsupport::makeSmart({3, 3, 1}, {{1, 1, 0}, {1, 2, 0}});
  Script s(*sim, 0);
  s.onStart = [&](vs_ctx* c) {
    BOOST_CHECK(c->state == nullptr);  // state_size 0: no state
    BOOST_CHECK_EQUAL(c->api->face_count(c), 4);
    BOOST_CHECK_EQUAL(c->api->set_value(c, 40 + std::int32_t(c->block)), VS_OK);
    std::int32_t acc[3];
    BOOST_CHECK_EQUAL(c->api->read_sensor(c, VS_SENSOR_ACCEL, acc), VS_ERR_UNSUPPORTED);
    BOOST_CHECK_EQUAL(c->api->color(c), 0x4080FFu);
    BOOST_CHECK_EQUAL(c->api->neighbor(c, c->block == 0 ? targets::kSBNorth : targets::kSBSouth),
                      1u - c->block);
  };
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(sim->displayValue(0), 40);
  BOOST_CHECK_EQUAL(sim->displayValue(1), 41);
}

BOOST_AUTO_TEST_CASE(start_comes_before_every_other_event_of_a_block) {
  // The ABI promises `start` once per block at time 0, then `event`s. At t = 0 block 0 sends an
  // empty message (no transmission time), moves away from block 1, and block 2 is tapped at 0.
  auto sim = testsupport::makeSmart({4, 4, 1}, {{0, 0, 0}, {1, 0, 0}, {3, 3, 0}});
  Script s(*sim);
  s.onStart = [&](vs_ctx* c) {
    if (c->block != 0) return;
    BOOST_CHECK_EQUAL(c->api->send(c, targets::kSBEast, nullptr, 0, 0), VS_OK);
    BOOST_CHECK_EQUAL(c->api->move(c, targets::kSBNorth), VS_OK);
  };
  sim->scheduleTap(2, 0);
  sim->runUntilEmpty();
  for (BlockId b = 0; b < 3; ++b) {
    const auto all = s.of(b);
    BOOST_REQUIRE(!all.empty());
    BOOST_CHECK_MESSAGE(all.front().kind == testsupport::kStartRec,
                        "block " << b << " got event kind " << all.front().kind << " before its start");
    BOOST_CHECK_EQUAL(s.of(b, testsupport::kStartRec).size(), 1u);
  }
  BOOST_CHECK_EQUAL(s.of(1, VS_EV_NEIGHBOR_REMOVED).size(), 1u);
  BOOST_CHECK_EQUAL(s.of(2, VS_EV_TAP).size(), 1u);
}

BOOST_AUTO_TEST_CASE(stale_timer_ids_cannot_cancel_a_newer_timer) {
  // Timer A fires; timer B, set in A's callback, may reuse A's slot: A's id must not cancel B.
  auto sim = testsupport::makeSmart({1, 1, 1}, {{0, 0, 0}});
  Script s(*sim);
  std::uint64_t a = 0, b = 0;
  s.onStart = [&](vs_ctx* c) {
    BOOST_CHECK_EQUAL(c->api->set_timer(c, kMillisecond, 1, &a), VS_OK);
    BOOST_CHECK_NE(a, 0u);
    BOOST_CHECK_EQUAL(c->api->cancel_timer(c, 0), VS_ERR_NOT_FOUND);
  };
  s.onEvent = [&](vs_ctx* c, const vs_event& ev) {
    if (ev.tag != 1) return;
    BOOST_CHECK_EQUAL(c->api->set_timer(c, kMillisecond, 2, &b), VS_OK);
    BOOST_CHECK_NE(a, b);
    BOOST_CHECK_EQUAL(c->api->cancel_timer(c, a), VS_ERR_NOT_FOUND);
  };
  sim->runUntilEmpty();
  const auto timers = s.of(0, VS_EV_TIMER);
  BOOST_REQUIRE_EQUAL(timers.size(), 2u);
  BOOST_CHECK_EQUAL(timers[1].tag, 2u);
  BOOST_CHECK_EQUAL(timers[1].timerId, b);
  BOOST_CHECK_EQUAL(timers[1].time, 2 * kMillisecond);
  BOOST_CHECK_EQUAL(sim->statistics().timersCancelled, 0u);
}

BOOST_AUTO_TEST_CASE(block_info_comes_from_the_info_callback) {
  auto sim = testsupport::makeSmart({3, 1, 1}, {{0, 0, 0}, {1, 0, 0}});
  Script s(*sim, sizeof(std::uint32_t));
  s.onStart = [&](vs_ctx* c) { *static_cast<std::uint32_t*>(c->state) = 10 + c->block; };
  s.onInfo = [&](vs_ctx* c, char* text, size_t capacity) -> int {
    std::string t = "block " + std::to_string(c->block) + " state " +
                    std::to_string(*static_cast<std::uint32_t*>(c->state));
    if (c->block == 1) t += std::string(300, '.');  // longer than a first guess of the host
    if (capacity) {
      const std::size_t n = std::min(capacity - 1, t.size());
      std::memcpy(text, t.data(), n);
      text[n] = '\0';
    }
    return int(t.size());
  };
  BOOST_CHECK_EQUAL(sim->blockInfo(0), "");  // no state before the run starts
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(sim->blockInfo(0), "block 0 state 10");
  BOOST_CHECK_EQUAL(sim->blockInfo(1), "block 1 state 11" + std::string(300, '.'));
}

BOOST_AUTO_TEST_CASE(abi_version_mismatch_and_null_callbacks) {
  auto sim = testsupport::makeSmart({2, 2, 1}, {{0, 0, 0}, {1, 0, 0}});
  const vs_blockcode wrong = {VS_ABI_VERSION + 1, "future", 0, nullptr, nullptr, nullptr, nullptr};
  BOOST_CHECK_THROW(sim->setBlockCode(&wrong), std::runtime_error);
  const vs_blockcode empty = {VS_ABI_VERSION, "empty", 8, nullptr, nullptr, nullptr, nullptr};
  sim->setBlockCode(&empty);
  sim->scheduleTap(0, kMillisecond);
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(sim->statistics().eventsProcessed, 3u);  // two starts and the tap, nobody listening
}

BOOST_AUTO_TEST_CASE(c_blockcode_loaded_with_dlopen_runs) {
  const std::string path = std::string(MELD_BINARY_DIR) + "/blockcodes/brownian_flood.so";
  Library lib;
  lib.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  BOOST_REQUIRE_MESSAGE(lib.handle,
                        "cannot load " << path << " (build the brownian_flood target): " << dlerror());
  auto entry = reinterpret_cast<vs_blockcode_entry_fn>(dlsym(lib.handle, VS_BLOCKCODE_ENTRY_SYMBOL));
  BOOST_REQUIRE(entry != nullptr);
  const vs_blockcode* code = entry();
  BOOST_REQUIRE(code != nullptr);
  BOOST_CHECK_EQUAL(code->abi_version, std::uint32_t(VS_ABI_VERSION));
  BOOST_CHECK_EQUAL(std::string(code->name), "brownian-flood");
  BOOST_CHECK_EQUAL(code->state_size, 2u);
  BOOST_CHECK(code->start && code->event && code->info);

  std::vector<std::uint64_t> prints;
  for (int run = 0; run < 2; ++run) {
    SimulationConfig cfg;
    cfg.seed = 5;
    auto sim = testsupport::makeWalkWorld(60, 9, cfg);  // dense, so the flood has somewhere to go
    sim->setBlockCode(code);
    int attached = 0;
    for (int f = 0; f < 4; ++f) attached += sim->world().neighbor(0, f) != kNoBlock;
    BOOST_REQUIRE_GT(attached, 0);  // block 0 floods its neighbors at t = 0 only
    sim->runUntil(30 * kSecond);
    BOOST_CHECK_EQUAL(sim->now(), 30 * kSecond);
    const Statistics& st = sim->statistics();
    BOOST_CHECK_GT(st.motionsStarted, 100u);
    BOOST_CHECK_GT(st.messagesReceived, 0u);
    BOOST_CHECK_EQUAL(sim->world().block(0).color, 0xFF0000u);
    std::size_t flooded = 0;
    for (BlockId b = 0; b < 60; ++b) {
      const auto* state = static_cast<const std::uint8_t*>(sim->blockState(b));
      const bool red = sim->world().block(b).color == 0xFF0000u;
      BOOST_CHECK_EQUAL(state[0] != 0, red);  // brownian_state.flooded mirrors the color
      flooded += red;
    }
    BOOST_CHECK_GT(flooded, 1u);
    // The info callback, given a context for block 0.
    vs_ctx ctx{nullptr, nullptr, 0, sim->blockState(0), nullptr};
    char text[32];
    BOOST_CHECK_EQUAL(code->info(&ctx, text, sizeof text), 7);
    BOOST_CHECK_EQUAL(std::string(text), "flooded");
    BOOST_CHECK_EQUAL(sim->blockInfo(0), "flooded");
    for (BlockId b = 0; b < 60; ++b)
      if (sim->world().block(b).color != 0xFF0000u) BOOST_CHECK_EQUAL(sim->blockInfo(b), "not reached");
    prints.push_back(sim->fingerprint());
  }
  BOOST_CHECK_EQUAL(prints[0], prints[1]);
}

BOOST_AUTO_TEST_CASE(programs_of_abi_2_still_run_and_others_are_refused) {
  // ABI 3 only added services at the end of the host table and one event kind: a program of ABI 2
  // runs unchanged (and gets no VS_EV_MOBILE); versions outside 2..3 are refused.
  BOOST_CHECK(vs_abi_supported(2) && vs_abi_supported(3));
  BOOST_CHECK(!vs_abi_supported(1) && !vs_abi_supported(4) && !vs_abi_supported(999));
  auto sim = testsupport::makeSmart({2, 1, 1}, {{0, 0, 0}, {1, 0, 0}});
  static int started = 0;
  static const vs_blockcode v2 = {2, "abi-2", 0, [](vs_ctx*) { ++started; }, nullptr, nullptr, nullptr};
  sim->setBlockCode(&v2);
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(started, 2);
  static const vs_blockcode v1 = {1, "abi-1", 0, nullptr, nullptr, nullptr, nullptr};
  auto other = testsupport::makeSmart({1, 1, 1}, {{0, 0, 0}});
  BOOST_CHECK_THROW(other->setBlockCode(&v1), std::runtime_error);
}
