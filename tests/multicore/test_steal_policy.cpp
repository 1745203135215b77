// support::StealPolicy: how many nodes a rebalance moves (threads and the simulated chip).
#define BOOST_TEST_MODULE steal_policy
#include <boost/test/unit_test.hpp>

#include "support/steal_policy.hpp"

using support::StealPolicy;

BOOST_AUTO_TEST_CASE(nothing_moves_without_a_node_to_spare) {
  BOOST_TEST(StealPolicy::nodesToGive(0, 0, 0.0, 1.0) == 0u);
  BOOST_TEST(StealPolicy::nodesToGive(1, 0, 0.0, 1.0) == 0u);
  BOOST_TEST(StealPolicy::nodesToGive(5, 4, 0.0, 1.0) == 0u);
  BOOST_TEST(StealPolicy::nodesToGive(2, 0, 0.0, 1.0) == 1u);
}

BOOST_AUTO_TEST_CASE(an_idle_taker_gets_half_the_difference_of_the_queues) {
  BOOST_TEST(StealPolicy::nodesToGive(400, 0, 0.0, 1.0) == 200u);
  BOOST_TEST(StealPolicy::nodesToGive(399, 1, 0.0, 1.0) == 199u);
  BOOST_TEST(StealPolicy::nodesToGive(1000, 200, 0.1, 1.0) == 400u);
}

BOOST_AUTO_TEST_CASE(a_taker_that_was_busy_most_of_the_time_gets_its_share_of_the_imbalance) {
  // Busy 80 % against 100 %: a tenth of the giver's queued work evens them out.
  BOOST_TEST(StealPolicy::nodesToGive(10000, 100, 0.0, 0.2) == 1000u);
  // Giver busy 90 %, taker 60 %: 0.3 / (2 x 0.9) of the queue, rounded up.
  BOOST_TEST(StealPolicy::nodesToGive(900, 0, 0.1, 0.4) == 150u);
  // Never more than half the difference of the queues.
  BOOST_TEST(StealPolicy::nodesToGive(100, 90, 0.0, 0.5) == 5u);
}

BOOST_AUTO_TEST_CASE(an_idle_worker_that_was_busy_until_now_still_gets_one_node) {
  BOOST_TEST(StealPolicy::nodesToGive(10000, 0, 0.0, 0.0) == 1u);
  BOOST_TEST(StealPolicy::nodesToGive(10000, 0, 0.3, 0.1) == 1u);  // the giver idled more
}
