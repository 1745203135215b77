// Shared helpers of the simcore unit tests: building worlds, a scriptable block program that records
// every event it gets (a plain C-style vs_blockcode table whose callbacks forward to std::function
// hooks), and a random-walk + flood block program for whole-run tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "blinkyblocks/blinkyblocks.hpp"
#include "simcore/blockcode.h"
#include "simcore/rng.hpp"
#include "simcore/simulation.hpp"
#include "smartblocks/smartblocks.hpp"

namespace testsupport {

using simcore::BlockId;
using simcore::Cell;
using simcore::SimTime;

inline std::unique_ptr<simcore::Simulation> makeSim(const simcore::TargetSpec& target, simcore::GridSize size,
                                                    const std::vector<Cell>& cells,
                                                    const simcore::SimulationConfig& cfg = {}) {
  auto sim = std::make_unique<simcore::Simulation>(target, size, cfg);
  for (const Cell& c : cells)
    if (sim->addBlock(c) == simcore::kNoBlock) throw std::logic_error("test world: cannot place a block");
  return sim;
}
inline std::unique_ptr<simcore::Simulation> makeSmart(simcore::GridSize size, const std::vector<Cell>& cells,
                                                      const simcore::SimulationConfig& cfg = {}) {
  return makeSim(targets::smartBlocksTarget(), size, cells, cfg);
}
inline std::unique_ptr<simcore::Simulation> makeBlinky(simcore::GridSize size, const std::vector<Cell>& cells,
                                                       const simcore::SimulationConfig& cfg = {}) {
  return makeSim(targets::blinkyBlocksTarget(), size, cells, cfg);
}

// After a run with motions: every block settled in its own cell, exactly `blocks` cells taken (no
// reservation left behind), and every link seen from both ends.
inline void checkSettledWorld(const simcore::Simulation& sim, std::size_t blocks) {
  const simcore::World& w = sim.world();
  const simcore::GridSize g = w.size();
  std::size_t taken = 0;
  for (int z = 0; z < g.z; ++z)
    for (int y = 0; y < g.y; ++y)
      for (int x = 0; x < g.x; ++x) taken += !w.isFree(Cell{x, y, z});
  BOOST_CHECK_EQUAL(taken, blocks);
  for (BlockId id = 0; id < w.blockCount(); ++id) {
    BOOST_CHECK_EQUAL(w.block(id).motion, simcore::kNoBlock);
    BOOST_CHECK_EQUAL(w.settledAt(w.block(id).cell), id);
    for (int f = 0; f < w.faceCount(); ++f) {
      const BlockId n = w.neighbor(id, f);
      if (n != simcore::kNoBlock) BOOST_CHECK_EQUAL(w.neighbor(n, w.lattice().oppositeFace(w.block(id).cell, f)), id);
    }
  }
}

// One callback as the block program saw it. kind 0 stands for `start`.
struct Rec {
  SimTime time = 0;
  BlockId block = 0;
  int kind = 0;
  int face = -1;
  BlockId other = VS_NO_BLOCK;
  std::vector<std::uint8_t> data;
  std::uint64_t timerId = 0, tag = 0;
  int sensor = 0;
  std::int32_t values[3] = {0, 0, 0};
};
inline constexpr int kStartRec = 0;

// A block program built in the test. Callbacks are looked up by the simulation they run in (the
// ctx->host pointer), so several Scripts and Simulations can live in one process.
class Script {
 public:
  std::function<void(vs_ctx*)> onStart;
  std::function<void(vs_ctx*, const vs_event&)> onEvent;
  std::function<int(vs_ctx*, char*, size_t)> onInfo;
  std::vector<Rec> log;

  explicit Script(simcore::Simulation& sim, std::uint32_t stateSize = 0) : sim_(&sim) {
    table_ = vs_blockcode{VS_ABI_VERSION, "test-script", stateSize, &start, &event, &info, nullptr};
    registry()[sim_] = this;
    sim.setBlockCode(&table_);
  }
  ~Script() { registry().erase(sim_); }
  Script(const Script&) = delete;
  Script& operator=(const Script&) = delete;

  const vs_blockcode* table() const { return &table_; }

  // Recorded callbacks of one block (and of one kind, unless kind < 0).
  std::vector<Rec> of(BlockId block, int kind = -1) const {
    std::vector<Rec> out;
    for (const Rec& r : log)
      if (r.block == block && (kind < 0 || r.kind == kind)) out.push_back(r);
    return out;
  }
  std::size_t count(int kind) const {
    std::size_t n = 0;
    for (const Rec& r : log) n += r.kind == kind;
    return n;
  }

 private:
  static std::map<const void*, Script*>& registry() {
    static std::map<const void*, Script*> r;
    return r;
  }
  static Script& self(vs_ctx* c) { return *registry().at(c->host); }
  static void start(vs_ctx* c) {
    Script& s = self(c);
    Rec r;
    r.time = c->api->now(c);
    r.block = c->block;
    s.log.push_back(r);
    if (s.onStart) s.onStart(c);
  }
  static void event(vs_ctx* c, const vs_event* ev) {
    Script& s = self(c);
    Rec r;
    r.time = c->api->now(c);
    r.block = c->block;
    r.kind = ev->kind;
    r.face = ev->face;
    r.other = ev->other;
    if (ev->size)
      r.data.assign(static_cast<const std::uint8_t*>(ev->data),
                    static_cast<const std::uint8_t*>(ev->data) + ev->size);
    r.timerId = ev->timer_id;
    r.tag = ev->tag;
    r.sensor = ev->sensor;
    std::memcpy(r.values, ev->values, sizeof r.values);
    s.log.push_back(r);
    if (s.onEvent) s.onEvent(c, *ev);
  }
  static int info(vs_ctx* c, char* text, size_t capacity) {
    Script& s = self(c);
    return s.onInfo ? s.onInfo(c, text, capacity) : 0;
  }

  simcore::Simulation* sim_;
  vs_blockcode table_{};
};

// Observer that records drops, sends, traces and colors.
struct Recorder : simcore::SimulationObserver {
  struct Drop {
    std::uint32_t from;
    int face;
    std::uint32_t to;
    SimTime when;
  };
  std::vector<Drop> drops;
  std::vector<std::pair<std::uint32_t, std::string>> traces;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> colors;
  std::vector<simcore::Event> events;
  std::uint64_t sent = 0;
  void onEvent(const simcore::Simulation&, const simcore::Event& e) override { events.push_back(e); }
  void onMessageSent(const simcore::Simulation&, std::uint32_t, int, std::uint32_t, std::uint32_t,
                     SimTime) override {
    ++sent;
  }
  void onMessageDropped(const simcore::Simulation& s, std::uint32_t from, int face,
                        std::uint32_t to) override {
    drops.push_back({from, face, to, s.now()});
  }
  void onColorChanged(const simcore::Simulation&, std::uint32_t block, std::uint32_t rgb) override {
    colors.emplace_back(block, rgb);
  }
  void onBlockTrace(const simcore::Simulation&, std::uint32_t block, std::string_view text) override {
    traces.emplace_back(block, std::string(text));
  }
};

// Random walk + flood (like examples/c/brownian_flood.c, but terminating): every block waits a random
// time in [0, 1] s, tries a move through a random face, and repeats until it has tried
// kWalkAttempts times; block 0 floods a 4-byte hop count that every block forwards once.
inline constexpr std::uint8_t kWalkAttempts = 12;
struct WalkState {
  std::uint8_t attempts;
  std::uint8_t flooded;
};
namespace walk_detail {
inline void waitThenTry(vs_ctx* c) {
  WalkState* s = static_cast<WalkState*>(c->state);
  if (s->attempts++ < kWalkAttempts) vs_set_timer(c, vs_time(vs_random_below(c, 1000000001u)), 1);
}
inline void flood(vs_ctx* c, std::uint32_t hops) {
  static_cast<WalkState*>(c->state)->flooded = 1;
  vs_set_color(c, 0xFF0000);
  const std::uint32_t next = hops + 1;
  vs_send_all(c, &next, sizeof next, 0);
}
inline void start(vs_ctx* c) {
  if (c->block == 0) flood(c, 0);
  waitThenTry(c);
}
inline void event(vs_ctx* c, const vs_event* ev) {
  WalkState* s = static_cast<WalkState*>(c->state);
  switch (ev->kind) {
    case VS_EV_TIMER:
      if (vs_move(c, int(vs_random_below(c, std::uint32_t(c->api->face_count(c))))) != VS_OK) waitThenTry(c);
      break;
    case VS_EV_MOTION_END:
      waitThenTry(c);
      break;
    case VS_EV_NEIGHBOR_ADDED:
      // A flooded block tells newcomers, so the flood keeps spreading through motion.
      if (s->flooded) {
        const std::uint32_t hops = 1;
        c->api->send(c, ev->face, &hops, sizeof hops, 0);
      }
      break;
    case VS_EV_MESSAGE:
      if (!s->flooded && ev->size == 4) {
        std::uint32_t hops;
        std::memcpy(&hops, ev->data, 4);
        flood(c, hops);
      }
      break;
    default:
      break;
  }
}
}  // namespace walk_detail
inline const vs_blockcode kRandomWalk = {
    VS_ABI_VERSION, "random-walk", sizeof(WalkState), &walk_detail::start, &walk_detail::event,
    nullptr,        nullptr};

// Removes `centre`, whose every face has a neighbor, and checks that each neighbor hears exactly
// one NEIGHBOR_REMOVED on the face `opposite(f)` (the test's own expectation, not the lattice's)
// and loses the link, while the removed block hears nothing.
template <class Opposite>
void checkRemovalBreaksEveryLink(simcore::Simulation& sim, const Script& s, simcore::BlockId centre,
                                 int faces, Opposite opposite) {
  sim.runUntilEmpty();
  const simcore::World& w = sim.world();
  std::vector<std::pair<simcore::BlockId, int>> expected;  // (neighbor, its face towards the centre)
  for (int f = 0; f < faces; ++f) expected.emplace_back(w.neighbor(centre, f), opposite(f));
  for (const auto& [n, face] : expected) BOOST_REQUIRE_NE(n, simcore::kNoBlock);
  sim.removeBlock(centre);
  sim.runUntilEmpty();
  for (const auto& [n, face] : expected) {
    const auto removed = s.of(n, VS_EV_NEIGHBOR_REMOVED);
    BOOST_REQUIRE_EQUAL(removed.size(), 1u);
    BOOST_CHECK_EQUAL(removed[0].face, face);
    BOOST_CHECK_EQUAL(removed[0].other, centre);
    BOOST_CHECK_EQUAL(w.neighbor(n, face), simcore::kNoBlock);
  }
  BOOST_CHECK(s.of(centre, VS_EV_NEIGHBOR_REMOVED).empty());
}

// `n` Smart Blocks on distinct cells of an L x L grid, placed from (seed) with the kernel's RNG.
inline std::unique_ptr<simcore::Simulation> makeWalkWorld(std::uint32_t n, std::int32_t L,
                                                          const simcore::SimulationConfig& cfg,
                                                          std::uint64_t placementSeed = 7) {
  auto sim =
      std::make_unique<simcore::Simulation>(targets::smartBlocksTarget(), simcore::GridSize{L, L, 1}, cfg);
  std::uint64_t st = simcore::BlockRng::initialState(placementSeed, 12345);
  while (sim->world().blockCount() < n) {
    const std::uint32_t c = simcore::BlockRng::below(st, 12345, std::uint32_t(L * L));
    const Cell cell{std::int32_t(c % std::uint32_t(L)), std::int32_t(c / std::uint32_t(L)), 0};
    if (sim->world().isFree(cell)) sim->addBlock(cell);
  }
  sim->setBlockCode(&kRandomWalk);
  return sim;
}

// Two blocks competing for a cell: block 0 moves through `first` at the start; block 2 tries
// `second` at 0.5 s and again at 1.5 s. The move codes, in order, go to `codes`.
inline void competeForACell(Script& s, int first, int second, std::vector<std::pair<BlockId, int>>& codes) {
  s.onStart = [&codes, first](vs_ctx* ctx) {
    if (ctx->block == 0) codes.emplace_back(0, ctx->api->move(ctx, first));
    if (ctx->block == 2) {
      ctx->api->set_timer(ctx, 500 * simcore::kMillisecond, 0, nullptr);
      ctx->api->set_timer(ctx, 1500 * simcore::kMillisecond, 0, nullptr);
    }
  };
  s.onEvent = [&codes, second](vs_ctx* ctx, const vs_event& ev) {
    if (ctx->block == 2 && ev.kind == VS_EV_TIMER) codes.emplace_back(2, ctx->api->move(ctx, second));
  };
}

// kRandomWalk on a crowded patch, twice with the same seed: more than ten motions, every one
// ended, the world settled (checkSettledWorld), and the same fingerprint both times.
inline void checkRandomWalk(const simcore::TargetSpec& target, simcore::GridSize size, const std::vector<Cell>& cells,
                            std::uint64_t seed) {
  std::uint64_t prints[2] = {0, 0};
  for (int run = 0; run < 2; ++run) {
    simcore::SimulationConfig cfg;
    cfg.seed = seed;
    auto sim = makeSim(target, size, cells, cfg);
    sim->setBlockCode(&kRandomWalk);
    sim->runUntilEmpty();
    const simcore::Statistics& st = sim->statistics();
    BOOST_CHECK_GT(st.motionsStarted, 10u);
    BOOST_CHECK_EQUAL(st.motionsStarted, st.motionsEnded);
    checkSettledWorld(*sim, cells.size());
    prints[run] = sim->fingerprint();
  }
  BOOST_CHECK_EQUAL(prints[0], prints[1]);
}

}  // namespace testsupport
