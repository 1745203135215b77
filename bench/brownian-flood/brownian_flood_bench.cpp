// Benchmark B1 (brownian-flood): N Smart Blocks wander on an L x L grid (L = ceil(sqrt(2N))) while
// a flood spreads from block 0. Prints events, wall time, events/s, peak RSS, bytes per block and
// the run fingerprint. See bench/README.md.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "simcore/rng.hpp"
#include "simcore/simulation.hpp"
#include "smartblocks/smartblocks.hpp"

extern "C" const vs_blockcode* vs_blockcode_entry(void);

namespace {

struct Options {
  std::uint64_t blocks = 7000;
  simcore::SimTime until = 600 * simcore::kSecond;
  std::uint64_t seed = 1;
  simcore::FesKind fes = simcore::kDefaultFes;
  bool json = false;
  bool progress = isatty(2);
};

void usage(std::FILE* out) {
  std::fputs(
      "usage: brownian-flood [--blocks N] [--until T] [--seed S] [--fes heap|calendar|ladder] [--json] "
      "[--no-progress]\n"
      "  Benchmark B1: N Smart Blocks in Brownian motion on an L x L grid (L = ceil(sqrt(2N))),\n"
      "  flood from block 0, 1 Mbit/s links. Defaults: --blocks 7000 --until 600s --seed 1 --fes ladder.\n"
      "  T takes a unit: 600s, 10min, 1500ms (bare numbers are seconds).\n",
      out);
}

// One option's value into `o`; false (after a message) when it is malformed.
bool parseValue(const std::string& name, const char* v, Options& o) {
  char* end = nullptr;
  const char* expected = nullptr;
  if (name == "--blocks") {
    o.blocks = std::strtoull(v, &end, 10);
    if (*end || o.blocks == 0 || o.blocks > 100000000ull) expected = "a count in [1, 1e8]";
  } else if (name == "--seed") {
    o.seed = std::strtoull(v, &end, 10);
    if (*end || !*v) expected = "an integer";
  } else if (name == "--until") {
    const auto t = simcore::parseDuration(v);
    if (t)
      o.until = *t;
    else
      expected = "a duration like 600s or 10min";
  } else {
    const auto k = simcore::parseFesKind(v);
    if (k)
      o.fes = *k;
    else
      expected = "heap, calendar or ladder";
  }
  if (expected) std::fprintf(stderr, "brownian-flood: %s wants %s, got '%s'\n", name.c_str(), expected, v);
  return expected == nullptr;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* name) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "brownian-flood: %s needs a value\n", name);
        return nullptr;
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      usage(stdout);
      std::exit(0);
    } else if (a == "--blocks" || a == "--seed" || a == "--until" || a == "--fes") {
      const char* v = value(a.c_str());
      if (!v || !parseValue(a, v, o)) return false;
    } else if (a == "--json") {
      o.json = true;
    } else if (a == "--no-progress") {
      o.progress = false;
    } else {
      std::fprintf(stderr, "brownian-flood: unknown option '%s' (see --help)\n", a.c_str());
      return false;
    }
  }
  return true;
}

long peakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) return 2;

  const auto L = std::int32_t(std::ceil(std::sqrt(2.0 * double(o.blocks))));
  simcore::SimulationConfig cfg;
  cfg.seed = o.seed;
  cfg.fes = o.fes;
  simcore::Simulation sim(targets::smartBlocksTarget(), simcore::GridSize{L, L, 1}, cfg);

  // N distinct cells drawn uniformly (Knuth's selection sampling, one pass in row-major order), so
  // block ids follow rows: blocks that are neighbors in space are mostly near in memory too.
  std::uint64_t placement = simcore::BlockRng::initialState(o.seed, 0xFFFFFFF0u);
  const std::uint64_t cells = std::uint64_t(L) * std::uint64_t(L);
  std::uint64_t needed = o.blocks;
  sim.world().reserveBlocks(o.blocks);
  for (std::uint64_t c = 0; c < cells && needed > 0; ++c) {
    const std::uint64_t remaining = cells - c;
    const double u = double(simcore::BlockRng::next(placement, 0xFFFFFFF0u)) / 4294967296.0;
    if (double(remaining) * u < double(needed)) {
      sim.addBlock(simcore::Cell{std::int32_t(c % std::uint64_t(L)), std::int32_t(c / std::uint64_t(L)), 0},
                   0x4080FF);
      --needed;
    }
  }
  sim.setBlockCode(vs_blockcode_entry());

  const auto wall0 = std::chrono::steady_clock::now();
  const simcore::SimTime slice = o.until / 100 > 0 ? o.until / 100 : o.until;
  for (simcore::SimTime t = 0; t < o.until;) {
    t = std::min(o.until, t + slice);
    sim.runUntil(t);
    if (o.progress) {
      const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      std::fprintf(stderr, "\r  simulated %7.1f / %.1f s   %12" PRIu64 " events   %6.2f M events/s ",
                   double(t) / 1e9, double(o.until) / 1e9, sim.statistics().eventsProcessed,
                   w > 0 ? double(sim.statistics().eventsProcessed) / w / 1e6 : 0.0);
    }
    if (sim.pendingEvents() == 0) break;
  }
  if (o.progress) std::fputs("\n", stderr);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  const simcore::Statistics& s = sim.statistics();
  std::uint64_t flooded = 0;
  for (const simcore::Block& b : sim.world().blocks()) flooded += b.color == 0xFF0000;
  const long rssKb = peakRssKb();
  const double bytesPerBlock = double(rssKb) * 1024.0 / double(o.blocks);
  const double eps = double(s.eventsProcessed) / wall;

  if (o.json) {
    std::printf("{\"benchmark\":\"brownian-flood\",\"blocks\":%" PRIu64
                ",\"grid\":%d,\"simulated_s\":%.3f,\"seed\":%" PRIu64 ",\"fes\":\"%s\",\"events\":%" PRIu64
                ",\"wall_s\":%.3f,\"events_per_s\":%.0f,\"peak_rss_kb\":%ld,"
                "\"bytes_per_block\":%.1f,\"motions\":%" PRIu64 ",\"messages_sent\":%" PRIu64
                ",\"messages_dropped\":%" PRIu64 ",\"flooded\":%" PRIu64 ",\"max_queue\":%" PRIu64
                ",\"fingerprint\":\"%016" PRIx64 "\"}\n",
                o.blocks, L, double(sim.now()) / 1e9, o.seed, sim.fesName(), s.eventsProcessed, wall, eps,
                rssKb, bytesPerBlock, s.motionsStarted, s.messagesSent, s.messagesDropped, flooded,
                s.maxQueueSize, sim.fingerprint());
  } else {
    std::printf("brownian-flood: %" PRIu64 " blocks on a %dx%d grid, %.1f s simulated, seed %" PRIu64
                ", fes %s\n",
                o.blocks, L, L, double(sim.now()) / 1e9, o.seed, sim.fesName());
    std::printf("  %-18s %" PRIu64 "\n", "events", s.eventsProcessed);
    std::printf("  %-18s %.3f\n", "wall s", wall);
    std::printf("  %-18s %.2f M\n", "events/s", eps / 1e6);
    std::printf("  %-18s %.1f MB\n", "peak RSS", double(rssKb) / 1024.0);
    std::printf("  %-18s %.0f\n", "bytes per block", bytesPerBlock);
    std::printf("  %-18s %" PRIu64 " started, messages %" PRIu64 " sent / %" PRIu64 " dropped\n", "motions",
                s.motionsStarted, s.messagesSent, s.messagesDropped);
    std::printf("  %-18s %" PRIu64 " of %" PRIu64 " blocks\n", "flood reached", flooded, o.blocks);
    std::printf("  %-18s %016" PRIx64 "\n", "fingerprint", sim.fingerprint());
  }
  return 0;
}
