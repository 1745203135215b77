// The serial scheduler of spec §6.11 and the priority facts of §5.7.
#define BOOST_TEST_MODULE vm_serial_scheduler
#include <boost/test/unit_test.hpp>
#include <vector>

#include "meldvm/serial_scheduler.hpp"

using namespace meldvm;

namespace {
constexpr NodeId kNotANode = 0xFFFFFFFFu;  // what n holds until pop() sets it (pop is inline: GCC asks)

std::vector<NodeId> drain(SerialScheduler& s) {
  std::vector<NodeId> order;
  NodeId n = kNotANode;
  while (s.pop(n)) order.push_back(n);
  return order;
}
}  // namespace

BOOST_AUTO_TEST_CASE(equal_initial_priorities_pop_zero_then_from_the_last_node_down) {
  SerialScheduler s(SchedulingOptions{});
  s.start(5, 0, 5);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{0, 4, 3, 2, 1}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(without_initial_priorities_nodes_start_in_the_fifo_in_id_order) {
  SchedulingOptions o;
  o.noInitialPriorities = true;
  SerialScheduler s(o);
  s.start(4, 0, 4);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{0, 1, 2, 3}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(after_a_run_a_node_goes_to_the_fifo_and_the_heap_is_served_first) {
  SerialScheduler s(SchedulingOptions{});
  s.start(3, 0, 3);
  NodeId n = kNotANode;
  BOOST_REQUIRE(s.pop(n));
  BOOST_TEST(n == 0u);
  s.finished(0, true);  // back with no priority: FIFO, behind the heap
  BOOST_TEST(drain(s) == (std::vector<NodeId>{2, 1, 0}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(set_priority_raises_only_and_moves_a_waiting_node_to_the_heap) {
  SchedulingOptions o;
  o.noInitialPriorities = true;
  SerialScheduler s(o);
  s.start(4, 0, 4);  // FIFO 0 1 2 3
  s.setPriority(2, 5.0);
  s.setPriority(3, 7.0);
  s.setPriority(3, 1.0);  // lower: ignored
  BOOST_TEST(s.priority(3) == 7.0);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{3, 2, 0, 1}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(ascending_order_serves_smaller_values_first) {
  SchedulingOptions o;
  o.order = PriorityOrder::Asc;
  o.noInitialPriorities = true;
  SerialScheduler s(o);
  s.start(3, 0, 3);
  s.setPriority(1, 10.0);
  s.setPriority(2, 3.0);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{2, 1, 0}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(a_waiting_node_is_queued_once_and_a_finished_node_falls_back_to_its_default) {
  SchedulingOptions o;
  o.noInitialPriorities = true;
  SerialScheduler s(o);
  s.start(2, 0, 2);
  s.wake(1);
  s.wake(1);
  BOOST_TEST(s.waiting() == 2u);
  // As the established VM: only the default changes; the node takes it when its run ends.
  s.setDefaultPriority(0, 4.0);
  BOOST_TEST(s.priority(0) == s.noPriority());
  NodeId n = kNotANode;
  BOOST_REQUIRE(s.pop(n));
  BOOST_TEST(n == 0u);
  s.setPriority(0, 9.0);
  s.finished(0, false);
  BOOST_TEST(s.priority(0) == 4.0);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{1}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(add_priority_moves_a_fifo_node_to_the_heap_even_without_a_priority) {
  // The established VM's do_set_node_priority: a node in the FIFO leaves it for the heap whatever
  // add-priority gave it ("no priority" + 3 is still "no priority"), and the heap is served first;
  // remove-priority sends a node of the heap to the end of the FIFO.
  SchedulingOptions o;
  o.noInitialPriorities = true;
  SerialScheduler s(o);
  s.start(4, 0, 4);  // FIFO 0 1 2 3
  s.addPriority(2, 3.0);
  BOOST_TEST(s.priority(2) == s.noPriority());
  s.setPriority(3, 5.0);
  s.removePriority(3);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{2, 0, 1, 3}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(schedule_next_queues_an_idle_node_at_once) {
  SchedulingOptions o;
  o.noInitialPriorities = true;
  SerialScheduler s(o);
  s.start(3, 0, 2);  // FIFO 0 1; node 2 idle
  s.scheduleNext(2);
  BOOST_TEST(drain(s) == (std::vector<NodeId>{2, 0, 1}), boost::test_tools::per_element());
}
