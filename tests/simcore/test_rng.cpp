#define BOOST_TEST_MODULE simcore_rng
#include <array>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

#include "simcore/rng.hpp"
#include "test_support.hpp"

using namespace simcore;
using testsupport::Script;

namespace {

std::vector<std::uint32_t> draws(std::uint64_t seed, std::uint32_t id, std::size_t n) {
  std::uint64_t st = BlockRng::initialState(seed, id);
  std::vector<std::uint32_t> v(n);
  for (auto& x : v) x = BlockRng::next(st, id);
  return v;
}

double correlation(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b,
                   std::size_t lag) {
  const std::size_t n = std::min(a.size(), b.size() - lag);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = a[i], y = b[i + lag];
    sa += x;
    sb += y;
    saa += x * x;
    sbb += y * y;
    sab += x * y;
  }
  const double cov = sab / double(n) - (sa / double(n)) * (sb / double(n));
  const double va = saa / double(n) - (sa / double(n)) * (sa / double(n));
  const double vb = sbb / double(n) - (sb / double(n)) * (sb / double(n));
  return cov / std::sqrt(va * vb);
}

// Chi-square statistic of counts against a uniform expectation.
double chiSquare(const std::vector<std::uint64_t>& counts) {
  std::uint64_t total = 0;
  for (auto c : counts) total += c;
  const double e = double(total) / double(counts.size());
  double chi = 0;
  for (auto c : counts) chi += (double(c) - e) * (double(c) - e) / e;
  return chi;
}
constexpr double kChi5DofP001 = 20.515;  // 5 degrees of freedom, p = 0.001

}  // namespace

BOOST_AUTO_TEST_CASE(streams_of_different_blocks_differ_and_are_uncorrelated) {
  constexpr std::size_t kN = 10000;
  const std::uint32_t ids[] = {0, 1, 2, 3, 7, 8, 1000, 65535, 65536, 0x7FFFFFFE};
  std::vector<std::vector<std::uint32_t>> streams;
  for (std::uint32_t id : ids) streams.push_back(draws(42, id, kN));
  for (std::size_t i = 0; i < streams.size(); ++i) {
    // Each stream alone looks uniform: mean of u32 / 2^32 near 1/2 (sd 0.0029).
    double mean = 0;
    for (auto x : streams[i]) mean += double(x) / 4294967296.0;
    mean /= double(kN);
    BOOST_CHECK_SMALL(mean - 0.5, 0.015);
    for (std::size_t j = i + 1; j < streams.size(); ++j) {
      BOOST_TEST_CONTEXT("ids " << ids[i] << " and " << ids[j]) {
        const auto& a = streams[i];
        const auto& b = streams[j];
        // Equal draws at the same index: practically never for 32-bit values...
        std::size_t same = 0, sameLow = 0;
        for (std::size_t k = 0; k < kN; ++k) {
          same += a[k] == b[k];
          sameLow += (a[k] & 15u) == (b[k] & 15u);
        }
        BOOST_CHECK_LE(same, 1u);
        // ... and 1/16 of the time for their low 4 bits (sd 0.0024).
        BOOST_CHECK_SMALL(double(sameLow) / double(kN) - 1.0 / 16.0, 0.015);
        // Pearson correlation, also shifted by one and by seven draws (sd 0.01).
        for (std::size_t lag : {0u, 1u, 7u}) {
          BOOST_CHECK_SMALL(correlation(a, b, lag), 0.05);
          BOOST_CHECK_SMALL(correlation(b, a, lag), 0.05);
        }
        // Not a shifted copy: the first 4 draws of one do not occur as a window of the other.
        std::unordered_map<std::uint32_t, std::size_t> where;
        for (std::size_t k = 0; k < kN; ++k) where.emplace(b[k], k);
        auto it = where.find(a[0]);
        if (it != where.end() && it->second + 3 < kN)
          BOOST_CHECK(!(b[it->second + 1] == a[1] && b[it->second + 2] == a[2] && b[it->second + 3] == a[3]));
      }
    }
  }
  // Different seeds give different streams for the same id.
  const auto s1 = draws(1, 5, 64), s2 = draws(2, 5, 64);
  BOOST_CHECK(s1 != s2);
  BOOST_CHECK(draws(42, 5, 64) == draws(42, 5, 64));
}

BOOST_AUTO_TEST_CASE(same_seed_and_id_give_the_same_stream_whatever_the_creation_order) {
  // Two worlds with the same cells created in opposite orders: block ids are dense creation order,
  // so id k sits on different cells, but its stream depends on (seed, k) only. In the third world
  // block 0 draws a hundred extra numbers first: the other blocks' streams are unaffected.
  const std::vector<Cell> cells = {{0, 0, 0}, {2, 0, 0}, {4, 0, 0}, {0, 2, 0}, {2, 2, 0}};
  std::vector<Cell> reversed(cells.rbegin(), cells.rend());
  SimulationConfig cfg;
  cfg.seed = 77;
  using Draws = std::map<BlockId, std::vector<std::uint32_t>>;
  auto run = [&](const std::vector<Cell>& where, bool greedy) {
    auto sim = testsupport::makeSmart({5, 5, 1}, where, cfg);
    Script s(*sim);
    Draws out;
    s.onStart = [&](vs_ctx* ctx) {
      if (greedy && ctx->block == 0)
        for (int i = 0; i < 100; ++i) ctx->api->random_u32(ctx);
      auto& v = out[ctx->block];
      for (int i = 0; i < 8; ++i) v.push_back(ctx->api->random_u32(ctx));
      ctx->api->set_timer(ctx, (ctx->block + 1) * kMillisecond, 0, nullptr);
    };
    s.onEvent = [&](vs_ctx* ctx, const vs_event&) {
      for (int i = 0; i < 8; ++i) out[ctx->block].push_back(ctx->api->random_u32(ctx));
    };
    sim->runUntilEmpty();
    return out;
  };
  const Draws a = run(cells, false), b = run(reversed, false), c = run(cells, true);
  BOOST_REQUIRE_EQUAL(a.size(), cells.size());
  for (BlockId id = 0; id < cells.size(); ++id) {
    BOOST_TEST_CONTEXT("block " << id) {
      BOOST_CHECK(a.at(id) == b.at(id));
      BOOST_CHECK(a.at(id) == draws(77, id, 16));  // the kernel's host service is BlockRng
      if (id != 0) BOOST_CHECK(a.at(id) == c.at(id));
    }
  }
  BOOST_CHECK(a.at(0) != c.at(0));
  BOOST_CHECK(a.at(0) != a.at(1));
}

BOOST_AUTO_TEST_CASE(random_below_is_unbiased) {
  // Chi-square over 6 buckets, directly and through the host service of several blocks.
  std::vector<std::uint64_t> counts(6, 0);
  for (std::uint32_t id = 0; id < 10; ++id) {
    std::uint64_t st = BlockRng::initialState(3, id);
    for (int i = 0; i < 6000; ++i) {
      const std::uint32_t v = BlockRng::below(st, id, 6);
      BOOST_REQUIRE_LT(v, 6u);
      ++counts[v];
    }
  }
  BOOST_TEST_MESSAGE("chi2 direct = " << chiSquare(counts));
  BOOST_CHECK_LT(chiSquare(counts), kChi5DofP001);

  auto sim = testsupport::makeSmart({4, 4, 1}, {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {3, 3, 0}});
  Script s(*sim);
  std::vector<std::uint64_t> hostCounts(6, 0);
  std::uint64_t wide = 0, wideLow = 0;
  s.onStart = [&](vs_ctx* ctx) {
    BOOST_CHECK_EQUAL(ctx->api->random_below(ctx, 1), 0u);
    BOOST_CHECK_EQUAL(ctx->api->random_below(ctx, 0), 0u);
    for (int i = 0; i < 15000; ++i) {
      const std::uint32_t v = ctx->api->random_below(ctx, 6);
      BOOST_REQUIRE_LT(v, 6u);
      ++hostCounts[v];
    }
    // A bound of 3 * 2^30: a plain modulo would put half the draws below 2^30 instead of a third.
    for (int i = 0; i < 10000; ++i) {
      const std::uint32_t v = ctx->api->random_below(ctx, 3u << 30);
      BOOST_REQUIRE_LT(v, 3u << 30);
      ++wide;
      wideLow += v < (1u << 30);
    }
  };
  sim->runUntilEmpty();
  BOOST_TEST_MESSAGE("chi2 host = " << chiSquare(hostCounts));
  BOOST_CHECK_LT(chiSquare(hostCounts), kChi5DofP001);
  BOOST_CHECK_EQUAL(wide, 40000u);
  BOOST_CHECK_SMALL(double(wideLow) / double(wide) - 1.0 / 3.0, 0.02);  // sd 0.0024

  // The direct bounded draw with the same wide bound, and a biased modulo as a negative control of
  // the statistic.
  std::uint64_t st = BlockRng::initialState(5, 1);
  std::uint64_t low = 0, lowModulo = 0;
  for (int i = 0; i < 30000; ++i) {
    low += BlockRng::below(st, 1, 3u << 30) < (1u << 30);
    lowModulo += BlockRng::next(st, 1) % (3u << 30) < (1u << 30);
  }
  BOOST_CHECK_SMALL(double(low) / 30000.0 - 1.0 / 3.0, 0.02);
  BOOST_CHECK_GT(double(lowModulo) / 30000.0, 0.45);
}
