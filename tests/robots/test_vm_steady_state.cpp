// The VM allocates nothing per fact in the steady state (issue 3): a ball passed between two
// nodes a thousand times and a hundred thousand times costs the same number of allocations (the
// stores, mailboxes and queues reach their size in the first rounds and are reused after).
#define BOOST_TEST_MODULE robots_vm_steady_state
#include <boost/test/unit_test.hpp>

#include "../common/counting_new.hpp"
#include "meldvm/machine.hpp"
#include "robot_fixture.hpp"

namespace {

std::uint64_t allocationsFor(int rounds, std::string& dump) {
  const auto program = robots::compile(R"(
type route link(node, node).
type linear ball(node, int).
type seen(node, max int).
!link(@0, @1).
!link(@1, @0).
ball(@0, 0).
ball(X, N), !link(X, Y), N < )" + std::to_string(rounds) +
                                       R"( -o ball(Y, N + 1), !seen(X, N).
)");
  const std::uint64_t before = testcommon::allocations();
  {
    meldvm::Machine m(*program);
    m.run();
    dump = m.dump();
  }
  return testcommon::allocations() - before;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_hundred_times_more_facts_cost_no_more_allocations) {
  std::string small, large;
  const std::uint64_t a = allocationsFor(1000, small), b = allocationsFor(100000, large);
  BOOST_TEST_MESSAGE("allocations: " << a << " for 1,000 rounds, " << b << " for 100,000");
  BOOST_TEST(large.find("ball(100000)") != std::string::npos);
  BOOST_TEST(large.find("!seen(99999)") != std::string::npos);  // the max aggregate followed
  // The dump strings and hash tables may grow by a step or two more; per fact it would be 10^5.
  BOOST_TEST(b <= a + 64);
}
