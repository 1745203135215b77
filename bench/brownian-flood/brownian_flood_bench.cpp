// Benchmark B1 (brownian-flood): N Smart Blocks wander on an L x L grid (L = ceil(sqrt(2N))) while
// a flood spreads from block 0 (--epidemic: also to every block that comes next to an informed
// one). Prints events, wall time, events/s, peak RSS, bytes per block, the blocks reached at each
// tenth of the run and the run fingerprint. See bench/README.md.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "simcore/rng.hpp"
#include "simcore/simulation.hpp"
#include "smartblocks/smartblocks.hpp"

extern "C" const vs_blockcode* brownian_flood_variant(int epidemic);  // examples/c/brownian_flood.c

namespace {

struct Options {
  std::uint64_t blocks = 7000;
  simcore::SimTime until = 600 * simcore::kSecond;
  std::uint64_t seed = 1;
  simcore::FesKind fes = simcore::kDefaultFes;
  bool json = false;
  bool epidemic = false;
  bool progress = isatty(2);
};

void usage(std::FILE* out) {
  std::fputs(
      "usage: brownian-flood [--blocks N] [--until T] [--seed S] [--fes heap|calendar|ladder] [--epidemic]\n"
      "                      [--json] [--no-progress]\n"
      "  Benchmark B1: N Smart Blocks in Brownian motion on an L x L grid (L = ceil(sqrt(2N))),\n"
      "  flood from block 0, 1 Mbit/s links. Defaults: --blocks 7000 --until 600s --seed 1 --fes ladder.\n"
      "  --epidemic: an informed block also sends to every block that becomes its neighbor later.\n"
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
    } else if (a == "--epidemic") {
      o.epidemic = true;
    } else if (a == "--no-progress") {
      o.progress = false;
    } else {
      std::fprintf(stderr, "brownian-flood: unknown option '%s' (see --help)\n", a.c_str());
      return false;
    }
  }
  return true;
}

std::uint64_t reachedBlocks(const simcore::Simulation& sim) {  // informed blocks are red
  std::uint64_t n = 0;
  for (const simcore::Block& b : sim.world().blocks()) n += b.color == 0xFF0000;
  return n;
}

// "[[60.0,11],[120.0,40],...]" (json) or "60.0s:11 120.0s:40 ..." (text).
std::string reachedText(const std::vector<std::pair<double, std::uint64_t>>& reached, bool json) {
  std::string out;
  char item[64];
  for (std::size_t i = 0; i < reached.size(); ++i) {
    const char* separator = i == 0 ? "" : json ? "," : " ";
    std::snprintf(item, sizeof item, json ? "%s[%.1f,%" PRIu64 "]" : "%s%.1fs:%" PRIu64, separator,
                  reached[i].first, reached[i].second);
    out += item;
  }
  return json ? "[" + out + "]" : out;
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
  sim.setBlockCode(brownian_flood_variant(o.epidemic ? 1 : 0));

  // The run in a hundred slices (the progress line), counting the blocks reached after every tenth;
  // the counting's own time is left out of the wall time.
  std::vector<std::pair<double, std::uint64_t>> reached;  // (simulated s, blocks)
  double countingS = 0;
  const auto wall0 = std::chrono::steady_clock::now();
  for (int k = 1; k <= 100; ++k) {
    const simcore::SimTime t = o.until / 100 * k + (k == 100 ? o.until % 100 : 0);
    sim.runUntil(t);
    if (o.progress) {
      const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      std::fprintf(stderr, "\r  simulated %7.1f / %.1f s   %12" PRIu64 " events   %6.2f M events/s ",
                   double(t) / 1e9, double(o.until) / 1e9, sim.statistics().eventsProcessed,
                   w > 0 ? double(sim.statistics().eventsProcessed) / w / 1e6 : 0.0);
    }
    if (k % 10 == 0 || sim.pendingEvents() == 0) {
      const auto c0 = std::chrono::steady_clock::now();
      reached.emplace_back(double(t) / 1e9, reachedBlocks(sim));
      countingS += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
    }
    if (sim.pendingEvents() == 0) break;
  }
  if (o.progress) std::fputs("\n", stderr);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count() - countingS;

  const simcore::Statistics& s = sim.statistics();
  const std::uint64_t flooded = reached.back().second;
  const long rssKb = peakRssKb();
  const double bytesPerBlock = double(rssKb) * 1024.0 / double(o.blocks);
  const double eps = double(s.eventsProcessed) / wall;

  if (o.json) {
    std::printf("{\"benchmark\":\"brownian-flood\",\"blocks\":%" PRIu64
                ",\"grid\":%d,\"simulated_s\":%.3f,\"seed\":%" PRIu64 ",\"fes\":\"%s\",\"events\":%" PRIu64
                ",\"wall_s\":%.3f,\"events_per_s\":%.0f,\"peak_rss_kb\":%ld,"
                "\"bytes_per_block\":%.1f,\"motions\":%" PRIu64 ",\"messages_sent\":%" PRIu64
                ",\"messages_dropped\":%" PRIu64 ",\"flooded\":%" PRIu64 ",\"max_queue\":%" PRIu64
                ",\"epidemic\":%s,\"reached\":%s,\"fingerprint\":\"%016" PRIx64 "\"}\n",
                o.blocks, L, double(sim.now()) / 1e9, o.seed, sim.fesName(), s.eventsProcessed, wall, eps,
                rssKb, bytesPerBlock, s.motionsStarted, s.messagesSent, s.messagesDropped, flooded,
                s.maxQueueSize, o.epidemic ? "true" : "false", reachedText(reached, true).c_str(),
                sim.fingerprint());
  } else {
    std::printf(
        "brownian-flood%s: %" PRIu64 " blocks on a %dx%d grid, %.1f s simulated, seed %" PRIu64 ", fes %s\n",
        o.epidemic ? " --epidemic" : "", o.blocks, L, L, double(sim.now()) / 1e9, o.seed, sim.fesName());
    std::printf("  %-18s %" PRIu64 "\n", "events", s.eventsProcessed);
    std::printf("  %-18s %.3f\n", "wall s", wall);
    std::printf("  %-18s %.2f M\n", "events/s", eps / 1e6);
    std::printf("  %-18s %.1f MB\n", "peak RSS", double(rssKb) / 1024.0);
    std::printf("  %-18s %.0f\n", "bytes per block", bytesPerBlock);
    std::printf("  %-18s %" PRIu64 " started, messages %" PRIu64 " sent / %" PRIu64 " dropped\n", "motions",
                s.motionsStarted, s.messagesSent, s.messagesDropped);
    std::printf("  %-18s %" PRIu64 " of %" PRIu64 " blocks\n", "flood reached", flooded, o.blocks);
    std::printf("  %-18s %s\n", "reached over time", reachedText(reached, false).c_str());
    std::printf("  %-18s %016" PRIx64 "\n", "fingerprint", sim.fingerprint());
  }
  return 0;
}
