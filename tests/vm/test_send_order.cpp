// The delivery order of the facts one node run sends (send_order.hpp) against its definition:
// destinations, the first eight in first-send order and the others by node id; for one
// destination its predicates in the order of their first fact; for one destination and predicate
// the facts last sent first.
#define BOOST_TEST_MODULE vm_send_order
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <random>
#include <tuple>
#include <vector>

#include "../../vm/engine/src/send_order.hpp"

using meldvm::detail::SendOrder;

namespace {

struct Sent {
  std::uint64_t node, pred;
};

// The definition, as plainly as it can be said: one sort key per fact.
std::vector<std::uint32_t> definition(const std::vector<Sent>& sent) {
  std::vector<std::uint64_t> seen;  // the first eight destinations, in first-send order
  std::vector<std::tuple<std::uint64_t, std::uint64_t, std::int64_t, std::uint32_t>> keyed;
  for (std::uint32_t i = 0; i < sent.size(); ++i) {
    const auto at = std::find(seen.begin(), seen.end(), sent[i].node);
    if (at == seen.end() && seen.size() < SendOrder::kFirstSeen) seen.push_back(sent[i].node);
    const auto known = std::find(seen.begin(), seen.end(), sent[i].node);
    const std::uint64_t dest =
        known != seen.end() ? std::uint64_t(known - seen.begin()) : SendOrder::kFirstSeen + sent[i].node;
    // The predicate's rank: the index of its first fact to this destination.
    std::uint32_t first = i;
    for (std::uint32_t j = 0; j < i; ++j)
      if (sent[j].node == sent[i].node && sent[j].pred == sent[i].pred) {
        first = j;
        break;
      }
    keyed.emplace_back(dest, first, -std::int64_t(i), i);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> out;
  for (const auto& k : keyed) out.push_back(std::get<3>(k));
  return out;
}

std::vector<std::uint32_t> arranged(SendOrder& order, const std::vector<Sent>& sent) {
  const std::vector<std::uint32_t>* got = order.arrange(
      sent.size(), [&](std::size_t i) { return sent[i].node; }, [&](std::size_t i) { return sent[i].pred; });
  if (got) return *got;
  std::vector<std::uint32_t> sendingOrder(sent.size());  // nullptr: the sending order
  for (std::uint32_t i = 0; i < sent.size(); ++i) sendingOrder[i] = i;
  return sendingOrder;
}

}  // namespace

BOOST_AUTO_TEST_CASE(small_cases) {
  SendOrder order;
  BOOST_TEST(arranged(order, {}).empty());
  // Distinct destinations among the first eight: sending order.
  BOOST_TEST((arranged(order, {{5, 0}, {3, 0}, {9, 1}}) == std::vector<std::uint32_t>{0, 1, 2}));
  // One destination and predicate: last sent first.
  BOOST_TEST((arranged(order, {{4, 0}, {4, 0}, {4, 0}}) == std::vector<std::uint32_t>{2, 1, 0}));
  // Predicates of one destination in the order of their first fact, each reversed.
  BOOST_TEST((arranged(order, {{4, 1}, {4, 0}, {4, 1}, {4, 0}}) == std::vector<std::uint32_t>{2, 0, 3, 1}));
  // Past eight destinations, the others by node id (here 1 before 2, though 2 came first).
  std::vector<Sent> many;
  for (std::uint64_t n = 100; n < 108; ++n) many.push_back({n, 0});
  many.push_back({2, 0});
  many.push_back({1, 0});
  many.push_back({100, 0});
  const std::vector<std::uint32_t> got = arranged(order, many);
  BOOST_TEST((got == std::vector<std::uint32_t>{10, 0, 1, 2, 3, 4, 5, 6, 7, 9, 8}));
  BOOST_TEST((got == definition(many)));
}

BOOST_AUTO_TEST_CASE(random_runs_follow_the_definition) {
  // Runs of every size, few or many destinations and predicates, one SendOrder reused (as a
  // Machine reuses it), so that its kept lookup table serves runs of other sizes.
  std::mt19937_64 rng(7);
  SendOrder order;
  for (int run = 0; run < 3000; ++run) {
    const std::size_t n = rng() % (run % 10 == 0 ? 3000 : 40);
    const std::uint64_t nodes = 1 + rng() % (run % 3 == 0 ? 5 : 400), preds = 1 + rng() % 4;
    std::vector<Sent> sent;
    for (std::size_t i = 0; i < n; ++i) sent.push_back({rng() % nodes, rng() % preds});
    const std::vector<std::uint32_t> want = definition(sent);
    BOOST_TEST((arranged(order, sent) == want), "run " << run << " of " << n << " facts");
  }
}

BOOST_AUTO_TEST_CASE(runs_sent_destination_by_destination_follow_the_definition) {
  // The shape a comprehension over the neighbours sends (a fact or two of each predicate to one
  // destination, then the next), where the delivery order is often the sending order: blocks of
  // facts per destination, destinations past the eighth in rising or falling order, some sent to
  // twice, some predicates repeated within a block.
  std::mt19937_64 rng(11);
  SendOrder order;
  for (int run = 0; run < 3000; ++run) {
    const std::size_t blocks = rng() % 24;
    const bool rising = rng() % 2, repeats = rng() % 4 == 0, duplicates = rng() % 4 == 0;
    std::vector<Sent> sent;
    for (std::size_t b = 0; b < blocks; ++b) {
      std::uint64_t node = rising ? 10 * b + rng() % 10 : 1000 - 10 * b - rng() % 10;
      if (repeats && b > 0 && rng() % 5 == 0) node = sent[rng() % sent.size()].node;
      const std::size_t facts = 1 + rng() % 3;
      for (std::size_t k = 0; k < facts; ++k) sent.push_back({node, duplicates ? rng() % 2 : k});
    }
    BOOST_TEST((arranged(order, sent) == definition(sent)),
               "run " << run << " of " << sent.size() << " facts");
  }
}
