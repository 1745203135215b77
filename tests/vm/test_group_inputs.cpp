// GroupInputs: the per-node runs of aggregate inputs (one contiguous run per node, insertion order,
// runs growing through size classes and recycled when a group empties).
#define BOOST_TEST_MODULE vm_group_inputs
#include <boost/test/unit_test.hpp>
#include <initializer_list>
#include <vector>

#include "meldvm/group_inputs.hpp"
#include "meldvm/heap.hpp"

using namespace meldvm;

namespace {

Value I(int v) { return Value::fromInt(v); }

std::vector<int> ints(const GroupInputs& g, NodeId n, std::uint32_t field = 0) {
  std::vector<int> out;
  for (std::uint32_t i = 0; i < g.size(n); ++i) out.push_back(g.args(n, i)[field].asInt());
  return out;
}

// The inputs of `p(node, min int)` and the like: one int field.
struct IntInputs {
  TypeTable types;
  Heap heap{types};
  GroupInputs g{types, heap, {TypeTable::kInt}};
  void append(NodeId n, std::initializer_list<int> values) {
    for (int v : values) g.append(n, std::vector<Value>{I(v)}.data(), 1);
  }
};

}  // namespace

BOOST_FIXTURE_TEST_CASE(find_append_erase_keep_insertion_order, IntInputs) {
  g.addNodes(3);
  append(1, {5, 3, 9});
  BOOST_TEST(g.size(0) == 0u);
  BOOST_TEST(g.size(1) == 3u);
  BOOST_TEST(g.find(1, std::vector<Value>{I(3)}.data()) == 1u);
  BOOST_TEST(g.find(1, std::vector<Value>{I(4)}.data()) == GroupInputs::kNone);
  BOOST_TEST(g.find(0, std::vector<Value>{I(3)}.data()) == GroupInputs::kNone);  // per node
  g.setCount(1, 1, 7);
  BOOST_TEST(g.count(1, 1) == 7u);
  BOOST_TEST(g.count(1, 0) == 1u);
  g.erase(1, 0);  // later inputs move up, order kept
  BOOST_TEST(ints(g, 1) == std::vector<int>({3, 9}), boost::test_tools::per_element());
  BOOST_TEST(g.count(1, 0) == 7u);
}

BOOST_FIXTURE_TEST_CASE(erase_unordered_moves_the_last_input_into_the_gap, IntInputs) {
  g.addNodes(2);
  append(1, {5, 3, 9, 4});
  g.setCount(1, 3, 6);
  g.eraseUnordered(1, 0);
  BOOST_TEST(ints(g, 1) == std::vector<int>({4, 3, 9}), boost::test_tools::per_element());
  BOOST_TEST(g.count(1, 0) == 6u);  // the moved input keeps its count
  BOOST_TEST(g.find(1, std::vector<Value>{I(4)}.data()) == 0u);
  g.eraseUnordered(1, 2);  // the last one: nothing moves
  BOOST_TEST(ints(g, 1) == std::vector<int>({4, 3}), boost::test_tools::per_element());
  g.eraseUnordered(1, 0);
  g.eraseUnordered(1, 0);
  BOOST_TEST(g.size(1) == 0u);
  append(1, {8});  // an emptied group starts again
  BOOST_TEST(ints(g, 1) == std::vector<int>({8}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(runs_grow_through_size_classes_without_mixing_nodes) {
  TypeTable types;
  Heap heap(types);
  GroupInputs g(types, heap, {TypeTable::kInt, TypeTable::kNode});
  g.addNodes(2);
  std::vector<int> want0, want1;
  // Interleaved appends make the two nodes' runs move past each other as they grow.
  for (int v = 0; v < 100; ++v) {
    const Value a[2] = {I(v), Value::fromNode(std::uint32_t(v))};
    const Value b[2] = {I(1000 + v), Value::fromNode(7)};
    g.append(0, a, 1);
    want0.push_back(v);
    if (v % 3 == 0) {
      g.append(1, b, 2);
      want1.push_back(1000 + v);
    }
  }
  BOOST_TEST(ints(g, 0) == want0, boost::test_tools::per_element());
  BOOST_TEST(ints(g, 1) == want1, boost::test_tools::per_element());
  const Value probe[2] = {I(42), Value::fromNode(42)};
  BOOST_TEST(g.find(0, probe) == 42u);
  const Value otherNode[2] = {I(42), Value::fromNode(41)};  // every field must match
  BOOST_TEST(g.find(0, otherNode) == GroupInputs::kNone);
  BOOST_TEST(g.count(1, 3) == 2u);
}

BOOST_FIXTURE_TEST_CASE(an_emptied_run_is_reused_without_growing, IntInputs) {
  g.addNodes(1);
  for (int v = 0; v < 8; ++v) g.append(0, std::vector<Value>{I(v)}.data(), 1);
  g.clear(0);
  BOOST_TEST(g.size(0) == 0u);
  const std::size_t bytes = g.bytesReserved();
  for (int round = 0; round < 50; ++round) {
    for (int v = 0; v < 8; ++v) g.append(0, std::vector<Value>{I(v)}.data(), 1);
    while (g.size(0) != 0) g.erase(0, 0);
  }
  BOOST_TEST(g.bytesReserved() == bytes);
}

BOOST_AUTO_TEST_CASE(boxed_arguments_are_retained_and_released) {
  TypeTable types;
  Heap heap(types);
  const Value s = heap.makeString("hello");
  {
    GroupInputs g(types, heap, {TypeTable::kString});
    g.addNodes(1);
    g.append(0, &s, 1);
    g.append(0, &s, 1);
    BOOST_TEST(s.asObject()->refs == 3u);
    const Value other = heap.makeString("hello");  // equal value, another object
    BOOST_TEST(g.find(0, &other) == 0u);
    heap.release(TypeTable::kString, other);
    g.erase(0, 1);
    BOOST_TEST(s.asObject()->refs == 2u);
  }  // the destructor releases what is still stored
  BOOST_TEST(s.asObject()->refs == 1u);
  heap.release(TypeTable::kString, s);
}
