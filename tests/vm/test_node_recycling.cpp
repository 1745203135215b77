// The references to created nodes that stored values hold, and the reuse of deleted ids
// (node_references.hpp, node_recycling.hpp, §6.10).
#define BOOST_TEST_MODULE vm_node_recycling
#include <boost/test/unit_test.hpp>
#include <vector>

#include "meldvm/fact_table.hpp"
#include "meldvm/heap.hpp"
#include "meldvm/node_recycling.hpp"

using namespace meldvm;

BOOST_AUTO_TEST_CASE(stored_facts_count_their_node_fields) {
  TypeTable types;
  NodeReferences refs;
  refs.resize(8);
  Heap heap(types, &refs);
  BOOST_TEST(heap.holdsReferences(TypeTable::kNode));
  BOOST_TEST(!heap.holdsReferences(TypeTable::kInt));
  FactTable table(types, heap, {TypeTable::kNode, TypeTable::kInt}, false);
  ListHead head;
  const Value a[] = {Value::fromNode(5), Value::fromInt(1)};
  const Value b[] = {Value::fromNode(5), Value::fromInt(2)};
  const FactRef fa = table.insert(head, 0, a, 1);
  const FactRef fb = table.insert(head, 0, b, 1);
  BOOST_TEST(refs.count(5) == 2u);
  table.erase(head, fa);
  BOOST_TEST(refs.count(5) == 1u);
  BOOST_TEST(refs.dropped().empty());
  table.erase(head, fb);
  BOOST_TEST(refs.count(5) == 0u);
  BOOST_TEST(refs.dropped() == std::vector<NodeId>{5});
}

BOOST_AUTO_TEST_CASE(list_cells_count_their_nodes) {
  TypeTable types;
  NodeReferences refs;
  refs.resize(8);
  Heap heap(types, &refs);
  const TypeId nodes = types.list(TypeTable::kNode);
  const Value items[] = {Value::fromNode(3), Value::fromNode(4), Value::fromNode(3)};
  const Value list = heap.makeList(nodes, items);
  BOOST_TEST(refs.count(3) == 2u);
  BOOST_TEST(refs.count(4) == 1u);
  const Value longer = heap.cons(nodes, Value::fromNode(4), list);
  BOOST_TEST(refs.count(4) == 2u);
  heap.release(nodes, list);  // the longer list still holds the cells
  BOOST_TEST(refs.count(3) == 2u);
  heap.release(nodes, longer);
  BOOST_TEST(refs.count(3) == 0u);
  BOOST_TEST(refs.count(4) == 0u);
  BOOST_TEST(refs.dropped().size() == 2u);
}

BOOST_AUTO_TEST_CASE(without_counting_nodes_hold_nothing) {
  TypeTable types;
  Heap heap(types);
  BOOST_TEST(!heap.holdsReferences(TypeTable::kNode));
  FactTable table(types, heap, {TypeTable::kNode}, false);
  ListHead head;
  const Value a[] = {Value::fromNode(1)};
  table.erase(head, table.insert(head, 0, a, 1));  // nothing to retain or release
  BOOST_TEST(head.size == 0u);
}

BOOST_AUTO_TEST_CASE(ids_not_yet_created_are_not_counted) {
  NodeReferences refs;
  refs.resize(4);
  refs.add(9);
  refs.drop(9);
  refs.drop(2);  // never added: no underflow, not reported
  BOOST_TEST(refs.count(9) == 0u);
  BOOST_TEST(refs.count(2) == 0u);
  BOOST_TEST(refs.dropped().empty());
}

BOOST_AUTO_TEST_CASE(freed_ids_are_reused_last_first_and_at_most_32_kept) {
  NodeRecycling recycling(true);
  BOOST_TEST(recycling.references() != nullptr);
  BOOST_TEST(NodeRecycling(false).references() == nullptr);
  NodeId id = 0;
  BOOST_TEST(!recycling.reuse(id));
  for (NodeId n = 100; n < 140; ++n) recycling.freed(n);  // 40 deleted: 100..131 kept
  std::vector<NodeId> got;
  while (recycling.reuse(id)) got.push_back(id);
  BOOST_TEST(got.size() == 32u);
  BOOST_TEST(got.front() == 131u);
  BOOST_TEST(got.back() == 100u);
}
