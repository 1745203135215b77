// Where a threaded run's nodes start (threads::NodeDirectory): contiguous ranges of about equal
// weight, a node weighing one plus the facts of its axioms, so that a graph whose busy nodes sit
// at one end does not leave one thread with most of the work.
#define BOOST_TEST_MODULE threads_node_directory
#include <atomic>
#include <boost/test/unit_test.hpp>
#include <thread>
#include <vector>

#include "../meldc/compile_source.hpp"
#include "meldvm/node_directory.hpp"

using meldvm::NodeId;
using meldvm::threads::NodeDirectory;

namespace {

// Source node @0 holds ten facts, @1..@10 one each. With no edges meldc numbers them in reverse
// (§6.1): internal node 10 is @0, the heavy one; 0..9 weigh 2 each, 10 weighs 11 (31 in all).
const char* kSkewed = R"(
type item(node, int).
type linear done(node).
!item(A, _) -o done(A).
!item(@0, 1). !item(@0, 2). !item(@0, 3). !item(@0, 4). !item(@0, 5).
!item(@0, 6). !item(@0, 7). !item(@0, 8). !item(@0, 9). !item(@0, 10).
!item(@1, 1). !item(@2, 1). !item(@3, 1). !item(@4, 1). !item(@5, 1).
!item(@6, 1). !item(@7, 1). !item(@8, 1). !item(@9, 1). !item(@10, 1).
)";

std::vector<NodeId> cuts(const NodeDirectory& d) {
  std::vector<NodeId> c;
  for (meldvm::ThreadId t = 0; t < d.threads(); ++t) c.push_back(d.firstOwned(t));
  c.push_back(d.endOwned(d.threads() - 1));
  return c;
}

}  // namespace

BOOST_AUTO_TEST_CASE(ranges_of_equal_weight_not_of_equal_node_counts) {
  const auto p = compileSource(kSkewed);
  const NodeDirectory two(*p, 11, 2, false);
  // 0..6 weigh 14, 7..10 weigh 17: the nearest cut to 15.5 (equal counts would give 10 and 21).
  BOOST_TEST(cuts(two) == (std::vector<NodeId>{0, 7, 11}), boost::test_tools::per_element());
  BOOST_TEST(two.ownerOf(6) == 0u);
  BOOST_TEST(two.ownerOf(7) == 1u);
  const NodeDirectory three(*p, 11, 3, false);
  // Goals 10 and 20: 0..4 weigh 10, 5..9 another 10, the heavy node alone.
  BOOST_TEST(cuts(three) == (std::vector<NodeId>{0, 5, 10, 11}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(equal_weights_cut_as_equal_counts) {
  const auto p = compileSource(R"(
type item(node, int).
type linear done(node).
!item(A, _) -o done(A).
!item(@0, 1). !item(@1, 1). !item(@2, 1). !item(@3, 1). !item(@4, 1). !item(@5, 1).
!item(@6, 1). !item(@7, 1). !item(@8, 1). !item(@9, 1). !item(@10, 1). !item(@11, 1).
)");
  BOOST_TEST(cuts(NodeDirectory(*p, 12, 3, false)) == (std::vector<NodeId>{0, 4, 8, 12}),
             boost::test_tools::per_element());
  BOOST_TEST(cuts(NodeDirectory(*p, 12, 4, false)) == (std::vector<NodeId>{0, 3, 6, 9, 12}),
             boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(nodes_beyond_the_program_weigh_one_and_more_threads_than_nodes_leave_some_empty) {
  const auto p = compileSource(kSkewed);
  // 32 nodes: 21 more of weight 1 (52 in all). The goal, 26, falls in the heavy node (20 before
  // it, 31 after): it goes to thread 0, whose share ends nearer the goal so (31 against 21, not
  // 20 against 32).
  const NodeDirectory wide(*p, 32, 2, false);
  BOOST_TEST(cuts(wide) == (std::vector<NodeId>{0, 11, 32}), boost::test_tools::per_element());
  const NodeDirectory many(*p, 3, 5, false);
  const std::vector<NodeId> c = cuts(many);
  BOOST_TEST(c.front() == 0u);
  BOOST_TEST(c.back() == 3u);
  for (std::size_t t = 0; t + 1 < c.size(); ++t) BOOST_TEST(c[t] <= c[t + 1]);
  for (NodeId n = 0; n < 3; ++n) BOOST_TEST(many.ownerOf(n) < 5u);
}

// Owners are packed several to a 64-bit word (1 bit each at two threads, 16 at up to 1024), and
// threads move nodes of the same word at the same time in a rebalance: every node keeps the
// owner last given to it, whatever its neighbours in the word do.
BOOST_AUTO_TEST_CASE(packed_owners_move_one_node_at_a_time) {
  const auto p = compileSource(kSkewed);
  for (const meldvm::ThreadId threads : {1u, 2u, 3u, 4u, 5u, 16u, 17u, 256u, 257u, 1024u}) {
    const NodeId nodes = 200;  // several words at every width, the last one partly used
    NodeDirectory d(*p, nodes, threads, false);
    for (NodeId n = 0; n < nodes; ++n) {
      BOOST_TEST(d.ownerOf(n) < threads);
      BOOST_TEST(d.firstOwned(d.ownerOf(n)) <= n);
      BOOST_TEST(n < d.endOwned(d.ownerOf(n)));
    }
    std::vector<meldvm::ThreadId> expected(nodes);
    for (NodeId n = 0; n < nodes; ++n) {
      expected[n] = meldvm::ThreadId((n * 7 + 3) % threads);
      d.moveNode(n, expected[n]);
    }
    d.moveNode(5, threads - 1), expected[5] = threads - 1;
    for (NodeId n = 0; n < nodes; ++n)
      BOOST_TEST(d.ownerOf(n) == expected[n], "node " << n << " of " << threads);
  }
}

BOOST_AUTO_TEST_CASE(concurrent_moves_in_one_word_keep_every_owner) {
  const auto p = compileSource(kSkewed);
  const NodeId nodes = 128;  // two words at two threads
  NodeDirectory d(*p, nodes, 2, false);
  // Thread 0 moves the even nodes to and fro, thread 1 the odd ones: each node has one mover, and
  // every word has nodes of both.
  std::vector<meldvm::ThreadId> start(nodes);
  for (NodeId n = 0; n < nodes; ++n) start[n] = d.ownerOf(n);
  std::atomic<int> ready{0};
  auto flip = [&](meldvm::ThreadId self) {
    ready.fetch_add(1);
    while (ready.load() < 2) {
    }
    for (int round = 0; round < 100000; ++round)
      for (NodeId n = self; n < nodes; n += 2) d.moveNode(n, d.ownerOf(n) ^ 1u);
  };
  std::thread a(flip, 0u), b(flip, 1u);
  a.join(), b.join();
  for (NodeId n = 0; n < nodes; ++n)
    BOOST_TEST(d.ownerOf(n) == start[n], "node " << n);  // an even count of flips
}
