// The per-node fact store (spec §6.3): linear facts in insertion order, consumption, in-place
// updates (§6.4.5), persistent facts with counts and retraction, compact predicates, node removal,
// and reference counts of the boxed values that facts hold.
#define BOOST_TEST_MODULE vm_store
#include <boost/test/unit_test.hpp>

#include "vm_fixture.hpp"

using namespace vmtest;

BOOST_AUTO_TEST_CASE(linear_facts_keep_insertion_order_per_node_and_predicate) {
  Store s;
  const PredId a = s.linear("a", {TypeTable::kInt});
  const PredId b = s.linear("b", {TypeTable::kInt, TypeTable::kNode});
  Database& db = s.open(3);
  for (int i = 1; i <= 4; ++i) db.addLinear(0, a, std::vector<Value>{I(i)}.data());
  db.addLinear(1, a, std::vector<Value>{I(7)}.data());
  db.addLinear(0, b, std::vector<Value>{I(5), N(2)}.data());
  BOOST_TEST(s.facts(0, a) == S({"a(1)", "a(2)", "a(3)", "a(4)"}), boost::test_tools::per_element());
  BOOST_TEST(s.facts(1, a) == S({"a(7)"}), boost::test_tools::per_element());
  BOOST_TEST(s.facts(2, a).empty());
  BOOST_TEST(s.facts(0, b) == S({"b(5, @2)"}), boost::test_tools::per_element());
  BOOST_TEST(db.factCount(0, a) == 4u);
  BOOST_TEST(db.factCount(2, b) == 0u);

  // Identical linear facts are distinct resources.
  db.addLinear(2, a, std::vector<Value>{I(9)}.data());
  db.addLinear(2, a, std::vector<Value>{I(9)}.data());
  BOOST_TEST(db.factCount(2, a) == 2u);
}

BOOST_AUTO_TEST_CASE(consuming_keeps_the_order_of_the_rest) {
  Store s;
  const PredId a = s.linear("a", {TypeTable::kInt});
  Database& db = s.open(1);
  std::vector<FactRef> refs;
  for (int i = 1; i <= 5; ++i) refs.push_back(db.addLinear(0, a, std::vector<Value>{I(i)}.data()));
  db.consume(0, a, refs[2]);  // middle
  db.consume(0, a, refs[0]);  // first
  db.consume(0, a, refs[4]);  // last
  BOOST_TEST(s.facts(0, a) == S({"a(2)", "a(4)"}), boost::test_tools::per_element());
  BOOST_TEST(db.factCount(0, a) == 2u);
  // New facts go to the end even though they reuse freed slots.
  db.addLinear(0, a, std::vector<Value>{I(6)}.data());
  db.addLinear(0, a, std::vector<Value>{I(7)}.data());
  BOOST_TEST(s.facts(0, a) == S({"a(2)", "a(4)", "a(6)", "a(7)"}), boost::test_tools::per_element());
  // Consume while iterating: read next first.
  for (FactRef f = db.first(0, a); f != kNoFact;) {
    const FactRef nx = db.next(a, f);
    if (db.args(a, f)[0].asInt() % 2 == 0) db.consume(0, a, f);
    f = nx;
  }
  BOOST_TEST(s.facts(0, a) == S({"a(7)"}), boost::test_tools::per_element());
  db.consume(0, a, db.first(0, a));
  BOOST_TEST(db.first(0, a) == kNoFact);
  BOOST_TEST(db.factCount(0, a) == 0u);
}

// §6.4.5: "go(A), a(A,2) -o a(A,20)" leaves 1, 3, 20 (moved to the end); with the updated fact
// bound by the outermost loop it keeps its place: 1, 20, 3.
BOOST_AUTO_TEST_CASE(in_place_update_keeps_or_moves_the_fact) {
  Store s;
  const PredId a = s.linear("a", {TypeTable::kInt});
  Database& db = s.open(2);
  FactRef two[2];
  for (NodeId n = 0; n < 2; ++n)
    for (int i = 1; i <= 3; ++i) {
      const FactRef f = db.addLinear(n, a, std::vector<Value>{I(i)}.data());
      if (i == 2) two[n] = f;
    }
  db.updateLinear(0, a, two[0], std::vector<Value>{I(20)}.data(), true);
  db.updateLinear(1, a, two[1], std::vector<Value>{I(20)}.data(), false);
  BOOST_TEST(s.facts(0, a) == S({"a(1)", "a(3)", "a(20)"}), boost::test_tools::per_element());
  BOOST_TEST(s.facts(1, a) == S({"a(1)", "a(20)", "a(3)"}), boost::test_tools::per_element());
  // Moving the last fact to the back changes nothing.
  db.updateLinear(0, a, two[0], std::vector<Value>{I(21)}.data(), true);
  BOOST_TEST(s.facts(0, a) == S({"a(1)", "a(3)", "a(21)"}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(persistent_facts_count_copies_and_retract) {
  Store s;
  const PredId e = s.persistent("edge", {TypeTable::kNode, TypeTable::kInt});
  Database& db = s.open(2);
  const std::vector<Value> x{N(1), I(5)}, y{N(1), I(6)};
  Change c = db.derive(0, e, x.data());
  BOOST_TEST(c.added);
  BOOST_TEST(c.count == 1u);
  BOOST_TEST(c.addedArgs.size() == 2u);
  BOOST_TEST(c.addedArgs[1].asInt() == 5);
  c = db.derive(0, e, x.data());  // a copy: counted, not new (only the first copy triggers rules)
  BOOST_TEST(!c.added);
  BOOST_TEST(c.count == 2u);
  c = db.derive(0, e, y.data(), 3);
  BOOST_TEST(c.added);
  BOOST_TEST(c.count == 3u);
  db.derive(1, e, x.data());  // another node: a separate fact
  BOOST_TEST(s.facts(0, e) == S({"!edge(@1, 5) x2", "!edge(@1, 6) x3"}), boost::test_tools::per_element());
  BOOST_TEST(s.facts(1, e) == S({"!edge(@1, 5)"}), boost::test_tools::per_element());
  BOOST_TEST(db.find(0, e, y.data()) != kNoFact);

  c = db.retract(0, e, x.data());
  BOOST_TEST(c.found);
  BOOST_TEST(!c.removed);
  BOOST_TEST(c.count == 1u);
  c = db.retract(0, e, x.data());
  BOOST_TEST(c.removed);
  BOOST_TEST(c.count == 0u);
  BOOST_TEST(c.removedArgs[0].asNode() == 1u);
  BOOST_TEST(c.removedArgs[1].asInt() == 5);
  c = db.retract(0, e, x.data());
  BOOST_TEST(!c.found);
  BOOST_TEST(!c.removed);
  c = db.retract(0, e, y.data(), 5);  // more than stored: the fact goes
  BOOST_TEST(c.removed);
  BOOST_TEST(db.factCount(0, e) == 0u);
  BOOST_TEST(db.find(0, e, y.data()) == kNoFact);
  BOOST_TEST(s.facts(1, e) == S({"!edge(@1, 5)"}), boost::test_tools::per_element());
  // Re-deriving after removal is a new first copy.
  BOOST_TEST(db.derive(0, e, x.data()).added);
}

BOOST_AUTO_TEST_CASE(compact_predicates_append_every_derivation) {
  Store s;
  const PredId c = s.persistent("axiom", {TypeTable::kInt}, true);
  Database& db = s.open(1);
  for (int v : {3, 1, 3}) BOOST_TEST(db.derive(0, c, std::vector<Value>{I(v)}.data()).added);
  BOOST_TEST(s.facts(0, c) == S({"!axiom(3)", "!axiom(1)", "!axiom(3)"}), boost::test_tools::per_element());
  BOOST_TEST(db.retract(0, c, std::vector<Value>{I(3)}.data()).removed);
  BOOST_TEST(s.facts(0, c) == S({"!axiom(1)", "!axiom(3)"}), boost::test_tools::per_element());
}

// A node's literal axioms are stored a predicate at a time: the same facts, counts and order as
// one derive() each, on plain, grouped and compact predicates.
BOOST_AUTO_TEST_CASE(deriving_facts_together_is_deriving_each) {
  Store s;
  const PredId e = s.persistent("edge", {TypeTable::kNode, TypeTable::kInt});
  const PredId c = s.persistent("axiom", {TypeTable::kNode, TypeTable::kInt}, true);
  Database& db = s.open(3);
  const std::vector<Value> facts{N(2), I(5), N(1), I(6), N(2), I(7), N(2), I(5), N(1), I(6)};
  for (const PredId p : {e, c}) {
    BOOST_TEST(db.deriveEach(0, p, facts.data(), 5));
    for (std::size_t i = 0; i < facts.size(); i += 2) db.derive(1, p, facts.data() + i);
    BOOST_TEST(s.facts(0, p) == s.facts(1, p), boost::test_tools::per_element());
  }
  BOOST_TEST(s.facts(0, e) == S({"!edge(@2, 5) x2", "!edge(@2, 7)", "!edge(@1, 6) x2"}),
             boost::test_tools::per_element());
  BOOST_TEST(db.factCount(0, c) == 5u);
  // Only copies of stored facts: nothing new becomes visible.
  BOOST_TEST(!db.deriveEach(0, e, facts.data(), 2));
  BOOST_TEST(s.facts(0, e).front() == "!edge(@2, 5) x3");
  BOOST_TEST(!db.deriveEach(2, e, facts.data(), 0));
  BOOST_TEST(db.factCount(2, e) == 0u);
  // A compact table appends: into freed slots first, then fresh ones, in order either way.
  db.retract(0, c, facts.data() + 2);
  db.retract(0, c, facts.data());
  BOOST_TEST(db.deriveEach(2, c, facts.data(), 5));
  BOOST_TEST(s.facts(2, c) == s.facts(1, c), boost::test_tools::per_element());
  // A compact predicate with an index (ITER_KEY on it) links each fact into its chain.
  Store t;
  const PredId k = t.persistent("keyed", {TypeTable::kNode, TypeTable::kInt}, true);
  Database& kd = t.open(1);
  const std::uint32_t ix = kd.requestIndex(k, 0);
  BOOST_TEST(kd.deriveEach(0, k, facts.data(), 5));
  std::vector<int> withTwo;
  for (FactRef f = kd.firstWithKey(0, k, ix, N(2)); f != kNoFact; f = kd.nextWithKey(k, ix, f))
    withTwo.push_back(kd.args(k, f)[1].asInt());
  BOOST_TEST(withTwo == (std::vector<int>{5, 7, 5}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(misuse_is_refused) {
  Store s;
  const PredId l = s.linear("l", {TypeTable::kInt});
  const PredId p = s.persistent("p", {TypeTable::kInt});
  PredicateDesc act;
  act.name = "setcolor";
  act.fields = {TypeTable::kInt, TypeTable::kInt, TypeTable::kInt};
  act.linear = true;
  act.action = true;
  const PredId a = s.preds.add(act);
  BOOST_CHECK_THROW(s.persistent("P", {TypeTable::kInt}), std::invalid_argument);  // names ignore case
  BOOST_CHECK_THROW(s.aggregate("bad", {TypeTable::kString}, AggregateKind::Min, 0), std::invalid_argument);
  BOOST_CHECK_THROW(s.aggregate("bad2", {TypeTable::kInt}, AggregateKind::Min, 1), std::invalid_argument);
  BOOST_TEST(s.preds.find("SETCOLOR") == a);
  BOOST_TEST(s.preds.find("nothing") == s.preds.size());
  Database& db = s.open(1);
  const Value v[3] = {I(1), I(2), I(3)};
  BOOST_CHECK_THROW(db.derive(0, l, v), std::logic_error);
  BOOST_CHECK_THROW(db.addLinear(0, p, v), std::logic_error);
  BOOST_CHECK_THROW(db.addLinear(0, a, v), std::logic_error);
  BOOST_CHECK_THROW(db.addLinear(1, l, v), std::out_of_range);
  db.addLinear(0, l, v);
  BOOST_CHECK_THROW(db.requestIndex(l, 0), std::logic_error);  // after facts exist
}

BOOST_AUTO_TEST_CASE(facts_hold_references_to_boxed_values) {
  Store s;
  const TypeId li = s.types.list(TypeTable::kInt);
  const PredId m = s.linear("msg", {TypeTable::kString, li});
  const PredId p = s.persistent("seen", {TypeTable::kString});
  Database& db = s.open(1);
  {
    Value str = s.heap.makeString("hello");
    Value list = s.heap.makeList(li, std::vector<Value>{I(1), I(2), I(3)});
    const Value args[2] = {str, list};
    db.addLinear(0, m, args);
    db.derive(0, p, args);
    db.derive(0, p, args);
    s.heap.release(TypeTable::kString, str);  // the facts keep them alive
    s.heap.release(li, list);
  }
  BOOST_TEST(s.heap.liveObjects() == 4u);
  BOOST_TEST(s.facts(0, m) == S({"msg(\"hello\", [1,2,3])"}), boost::test_tools::per_element());
  db.consume(0, m, db.first(0, m));
  BOOST_TEST(s.heap.liveObjects() == 1u);  // the string is still held by !seen
  // A retracted fact's values stay readable until the next change.
  Value key = s.heap.makeString("hello");
  db.retract(0, p, &key);
  const Change c = db.retract(0, p, &key);
  s.heap.release(TypeTable::kString, key);
  BOOST_TEST(c.removed);
  BOOST_TEST(std::string(stringOf(c.removedArgs[0])) == "hello");
  BOOST_TEST(s.heap.liveObjects() == 1u);
  db.addLinear(0, m, std::vector<Value>{s.heap.makeString("x"), Value::nil()}.data());
  BOOST_TEST(s.heap.liveObjects() == 1u);  // "hello" released, "x" (leaked ref + fact) live
}

BOOST_AUTO_TEST_CASE(removed_nodes_lose_their_facts) {
  Store s;
  const PredId a = s.linear("a", {TypeTable::kString});
  const PredId p = s.persistent("p", {TypeTable::kInt});
  Database& db = s.open(2);
  Value str = s.heap.makeString("gone");
  db.addLinear(1, a, &str);
  s.heap.release(TypeTable::kString, str);
  db.derive(1, p, std::vector<Value>{I(1)}.data());
  db.derive(0, p, std::vector<Value>{I(1)}.data());
  const NodeId created = db.addNodes(1);
  BOOST_TEST(created == 2u);
  BOOST_TEST(db.nodeCount() == 3u);
  db.removeNode(1);
  BOOST_TEST(!db.alive(1));
  BOOST_TEST(db.alive(2));
  BOOST_TEST(s.heap.liveObjects() == 0u);
  BOOST_TEST(db.factCount(0, p) == 1u);
  BOOST_CHECK_THROW(db.derive(1, p, std::vector<Value>{I(1)}.data()), std::out_of_range);
}

// §11: persistent facts come out grouped by their first field (the first level of the established
// VM's trie), groups in order of first appearance; linear facts stay in plain insertion order.
BOOST_AUTO_TEST_CASE(persistent_facts_group_by_first_field) {
  Store s;
  const PredId e = s.persistent("edge", {TypeTable::kNode, TypeTable::kInt});
  const PredId l = s.linear("link", {TypeTable::kNode, TypeTable::kInt});
  Database& db = s.open(1);
  const int order[][2] = {{1, 5}, {2, 6}, {1, 7}, {3, 8}, {2, 9}};
  for (const auto& o : order) {
    const Value args[2] = {N(NodeId(o[0])), I(o[1])};
    db.derive(0, e, args);
    db.addLinear(0, l, args);
  }
  BOOST_TEST(
      s.facts(0, e) == S({"!edge(@1, 5)", "!edge(@1, 7)", "!edge(@2, 6)", "!edge(@2, 9)", "!edge(@3, 8)"}),
      boost::test_tools::per_element());
  BOOST_TEST(s.facts(0, l) == S({"link(@1, 5)", "link(@2, 6)", "link(@1, 7)", "link(@3, 8)", "link(@2, 9)"}),
             boost::test_tools::per_element());
  // A group emptied and refilled joins the end.
  const Value one[2] = {N(1), I(5)}, seven[2] = {N(1), I(7)}, again[2] = {N(1), I(4)};
  db.retract(0, e, one);
  db.retract(0, e, seven);
  db.derive(0, e, again);
  BOOST_TEST(s.facts(0, e) == S({"!edge(@2, 6)", "!edge(@2, 9)", "!edge(@3, 8)", "!edge(@1, 4)"}),
             boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(a_full_table_grows_by_a_quarter_not_by_doubling) {
  // A threaded run's shards reserve their share of the facts and then grow as stolen nodes bring
  // theirs: doubling left each shard room for nearly all of them.
  Store s;
  const PredId p = s.linear("p", {TypeTable::kInt});
  Database& db = s.open(1);
  db.reserve(p, 1000);
  const std::size_t reserved = db.tableBytes();
  for (int i = 0; i < 1000; ++i) db.addLinear(0, p, std::vector<Value>{I(i)}.data());
  BOOST_TEST(db.tableBytes() == reserved);  // the reservation held them all
  db.addLinear(0, p, std::vector<Value>{I(1000)}.data());
  const std::size_t grown = db.tableBytes();
  BOOST_TEST(grown > reserved);
  BOOST_TEST(double(grown) <= 1.26 * double(reserved));
  BOOST_TEST(db.factCount(0, p) == 1001u);
}

BOOST_AUTO_TEST_CASE(node_heads_take_memory_only_for_the_pages_written) {
  // A shard of a threaded run stores the facts of some nodes only: untouched pages of 256 nodes
  // read as empty heads and cost nothing but the shared empty page.
  NodeHeads heads(4);
  heads.addNodes(10000);
  const std::size_t bare = heads.bytesReserved();
  BOOST_TEST(heads.of(9000)[3].first == kNoFact);
  BOOST_TEST(heads.of(9000)[3].size == 0u);
  heads.forWrite(5000)[2].size = 7;
  heads.forWrite(5100)[1].size = 8;  // the same page
  const std::size_t page = 256 * 4 * sizeof(ListHead);
  BOOST_TEST(heads.bytesReserved() - bare >= page);
  BOOST_TEST(heads.bytesReserved() - bare < page + 64);  // one page (and its entry in the list)
  BOOST_TEST(heads.of(5000)[2].size == 7u);
  BOOST_TEST(heads.of(5100)[1].size == 8u);
  BOOST_TEST(heads.of(5001)[2].size == 0u);
  BOOST_TEST(heads.of(9000)[2].size == 0u);  // the shared empty page was not written
  BOOST_TEST(heads.bytesReserved() < 10000 * 4 * sizeof(ListHead) / 4);
}

BOOST_AUTO_TEST_CASE(a_small_store_keeps_one_page_of_its_size_and_grows_past_it) {
  NodeHeads heads(2);
  heads.addNodes(3);  // a robot's machine: no page of 256 nodes for three
  BOOST_TEST(heads.bytesReserved() < 3 * 2 * sizeof(ListHead) + 64);
  heads.forWrite(2)[1].size = 5;
  heads.addNodes(1);  // a created node
  BOOST_TEST(heads.of(2)[1].size == 5u);
  BOOST_TEST(heads.of(3)[1].size == 0u);
  heads.addNodes(1000);  // past one page: the heads written stay
  BOOST_TEST(heads.of(2)[1].size == 5u);
  BOOST_TEST(heads.of(900)[0].first == kNoFact);
  heads.forWrite(900)[0].size = 9;
  BOOST_TEST(heads.of(900)[0].size == 9u);
  BOOST_TEST(heads.of(2)[1].size == 5u);
}

// A shard that gave most of its nodes away gives back the pages of their slots; the facts left
// keep their places, and new facts take the free slots and then the given-back ones before the
// table grows. Persistent facts stay found through the de-duplication table.
BOOST_AUTO_TEST_CASE(free_pages_go_back_and_their_slots_are_taken_again) {
  Store s;
  const PredId a = s.linear("a", {TypeTable::kInt});
  const PredId e = s.persistent("edge", {TypeTable::kNode, TypeTable::kInt});
  constexpr NodeId kNodes = 2000;
  constexpr int kFacts = 60;
  Database& db = s.open(kNodes);
  for (NodeId n = 0; n < kNodes; ++n)
    for (int i = 0; i < kFacts; ++i) {
      db.addLinear(n, a, std::vector<Value>{I(int(n) * 100 + i)}.data());
      db.derive(n, e, std::vector<Value>{N(n), I(i)}.data());
    }
  BOOST_TEST(db.releaseFreePages() == 0u);  // nothing is free
  // Nodes 0..1499 leave: their facts go (a quarter of the slots stays used).
  for (NodeId n = 0; n < 1500; ++n) {
    while (db.first(n, a) != kNoFact) db.consume(n, a, db.first(n, a));
    for (int i = 0; i < kFacts; ++i) db.retract(n, e, std::vector<Value>{N(n), I(i)}.data());
  }
  // 90,000 free slots of each table: about 2 MB of a's, 3 MB of edge's, nearly all whole pages;
  // edge's de-duplication table halves.
  const std::size_t reserved = db.tableBytes();
  const std::size_t given = db.releaseFreePages();
  BOOST_TEST(db.tableBytes() < reserved);
  BOOST_TEST(given > 4u * 1000 * 1000);
  BOOST_TEST(db.releaseFreePages() == 0u);  // given back already: nothing more to give
  auto expectA = [&](NodeId n) {
    std::vector<std::string> out;
    for (int i = 0; i < kFacts; ++i) out.push_back("a(" + std::to_string(int(n) * 100 + i) + ")");
    return out;
  };
  for (NodeId n = 1500; n < kNodes; n += 97) {
    BOOST_TEST(s.facts(n, a) == expectA(n), boost::test_tools::per_element());
    BOOST_TEST(db.factCount(n, e) == std::uint32_t(kFacts));
    BOOST_TEST(db.find(n, e, std::vector<Value>{N(n), I(kFacts - 1)}.data()) != kNoFact);
  }
  // The nodes come back: their facts fill the slots again, the slot arrays do not grow (the hash
  // table grows back to its size).
  for (NodeId n = 0; n < 1500; ++n)
    for (int i = 0; i < kFacts; ++i) {
      db.addLinear(n, a, std::vector<Value>{I(int(n) * 100 + i)}.data());
      BOOST_TEST_REQUIRE(db.derive(n, e, std::vector<Value>{N(n), I(i)}.data()).added);
    }
  BOOST_TEST(db.tableBytes() == reserved);
  for (NodeId n = 0; n < kNodes; n += 37) {
    BOOST_TEST(s.facts(n, a) == expectA(n), boost::test_tools::per_element());
    BOOST_TEST(!db.derive(n, e, std::vector<Value>{N(n), I(3)}.data()).added);  // a second copy
  }
}
