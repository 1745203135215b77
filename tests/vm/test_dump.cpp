// The database dump of spec §8, byte for byte, with expected texts worked out by hand from the
// rules of §8 (and the three examples printed there).
#define BOOST_TEST_MODULE vm_dump
#include <boost/test/unit_test.hpp>
#include <sstream>

#include "vm_fixture.hpp"

using namespace vmtest;

// basic.meld: type linear a(node, list node). a(@0, [@1, @2]). — renumbered @2->0, @1->1, @0->2.
BOOST_AUTO_TEST_CASE(example_basic) {
  Store s;
  const PredId a = s.linear("a", {s.types.list(TypeTable::kNode)});
  Database& db = s.open(3);
  Value l = s.heap.makeList(s.types.list(TypeTable::kNode), std::vector<Value>{N(1), N(0)});
  db.addLinear(2, a, &l);
  s.heap.release(s.types.list(TypeTable::kNode), l);
  BOOST_TEST(dumpDatabase(db) == "0\n1\n2\na([@1,@0])\n");
}

// linear-repeat.meld: persistent !a, linear b.
BOOST_AUTO_TEST_CASE(example_linear_repeat) {
  Store s;
  const PredId b = s.linear("b", {TypeTable::kInt});
  const PredId a = s.persistent("a", {TypeTable::kInt});
  Database& db = s.open(1);
  db.addLinear(0, b, std::vector<Value>{I(6)}.data());
  db.derive(0, a, std::vector<Value>{I(2)}.data());
  BOOST_TEST(dumpDatabase(db) == "0\n!a(2)\nb(6)\n");
}

// thread5: no normal nodes; the thread node is node 0.
BOOST_AUTO_TEST_CASE(example_thread5) {
  Store s;
  const PredId total = s.linear("total", {TypeTable::kInt});
  const PredId tl = s.persistent("thread-list", {s.types.list(TypeTable::kThread)});
  const PredId lt = s.persistent("leader-thread", {TypeTable::kThread});
  const PredId l = s.linear("l", {TypeTable::kInt});
  Database& db = s.open(1);
  db.addLinear(0, total, std::vector<Value>{I(0)}.data());
  Value threads = s.heap.makeList(s.types.list(TypeTable::kThread), std::vector<Value>{Value::fromThread(0)});
  db.derive(0, tl, &threads);
  s.heap.release(s.types.list(TypeTable::kThread), threads);
  db.derive(0, lt, std::vector<Value>{Value::fromThread(0)}.data());
  db.addLinear(0, l, std::vector<Value>{I(0)}.data());
  BOOST_TEST(dumpDatabase(db) == "0\nl(0)\n!leader-thread(#T0)\n!thread-list([#T0])\ntotal(0)\n");
}

// Facts sort as strings: numbers lexicographically (test `intensive`), '-' before digits, ')'
// before digits, insertion order irrelevant.
BOOST_AUTO_TEST_CASE(facts_sort_as_strings) {
  Store s;
  const PredId added = s.linear("added", {TypeTable::kInt});
  const PredId p = s.persistent("p", {TypeTable::kInt});
  Database& db = s.open(1);
  for (int v : {10001, 100, 100001, 10, 100000, 1000, 10000})
    db.addLinear(0, added, std::vector<Value>{I(v)}.data());
  for (int v : {2, -10, -1, -3}) db.derive(0, p, std::vector<Value>{I(v)}.data());
  BOOST_TEST(dumpDatabase(db) ==
             "0\n"
             "added(10)\nadded(100)\nadded(1000)\nadded(10000)\nadded(100000)\nadded(100001)\nadded(10001)\n"
             "!p(-1)\n!p(-10)\n!p(-3)\n!p(2)\n");
}

// Predicates by name only, byte-wise: upper case < '_' < lower case, prefixes first, '!' ignored.
BOOST_AUTO_TEST_CASE(predicates_sort_by_name_bytes) {
  Store s;
  const PredId lower = s.linear("a", {});
  const PredId mangled = s.persistent("__mangledname1", {TypeTable::kNode});
  const PredId upper = s.linear("Z", {});
  const PredId inverse = s.persistent("___robhgien", {TypeTable::kNode, TypeTable::kInt});
  const PredId nc = s.persistent("neighborCount", {TypeTable::kInt});
  const PredId nb = s.persistent("neighbor", {TypeTable::kNode, TypeTable::kInt});
  const PredId bpers = s.persistent("b", {});
  Database& db = s.open(1);
  db.addLinear(0, lower, nullptr);
  db.derive(0, mangled, std::vector<Value>{N(0)}.data());
  db.addLinear(0, upper, nullptr);
  db.derive(0, inverse, std::vector<Value>{N(0), I(3)}.data());
  db.derive(0, nc, std::vector<Value>{I(1)}.data());
  db.derive(0, nb, std::vector<Value>{N(0), I(3)}.data());
  db.derive(0, bpers, nullptr);
  BOOST_TEST(
      dumpDatabase(db) ==
      "0\nZ()\n!___robhgien(@0, 3)\n!__mangledname1(@0)\na()\n!b()\n!neighbor(@0, 3)\n!neighborCount(1)\n");
}

// Persistent facts once per copy; linear duplicates each print; nodes without facts print their
// id; nodes removed by the GC do not print at all.
BOOST_AUTO_TEST_CASE(copies_empty_nodes_and_removed_nodes) {
  Store s;
  const PredId p = s.persistent("p", {TypeTable::kInt});
  const PredId q = s.linear("q", {TypeTable::kString});
  Database& db = s.open(2);
  db.derive(1, p, std::vector<Value>{I(7)}.data(), 2);
  db.derive(1, p, std::vector<Value>{I(7)}.data());
  db.derive(1, p, std::vector<Value>{I(5)}.data());
  Value a = s.heap.makeString("a"), b = s.heap.makeString("B");
  db.addLinear(1, q, &a);
  db.addLinear(1, q, &b);
  db.addLinear(1, q, &a);
  const NodeId created = db.addNodes(2);
  db.addLinear(created, q, &a);
  s.heap.release(TypeTable::kString, a);
  s.heap.release(TypeTable::kString, b);
  BOOST_TEST(dumpDatabase(db) ==
             "0\n1\n!p(5)\n!p(7)\n!p(7)\n!p(7)\nq(\"B\")\nq(\"a\")\nq(\"a\")\n2\nq(\"a\")\n3\n");
  db.removeNode(2);
  BOOST_TEST(dumpDatabase(db) == "0\n1\n!p(5)\n!p(7)\n!p(7)\n!p(7)\nq(\"B\")\nq(\"a\")\nq(\"a\")\n3\n");
}

// Aggregates show only the current value; every value type in one fact; the stream overload.
BOOST_AUTO_TEST_CASE(aggregates_and_every_argument_type) {
  Store s;
  const PredId d = s.aggregate("dist", {TypeTable::kInt}, AggregateKind::Min, 0);
  const TypeId li = s.types.list(TypeTable::kInt);
  const TypeId pair[] = {TypeTable::kInt, TypeTable::kFloat};
  const TypeId st = s.types.structOf(pair), ar = s.types.array(TypeTable::kInt),
               se = s.types.set(TypeTable::kNode);
  const PredId all = s.linear("all", {TypeTable::kInt, TypeTable::kFloat, TypeTable::kBool, TypeTable::kNode,
                                      TypeTable::kThread, TypeTable::kString, li, st, ar, se});
  Database& db = s.open(1);
  for (int v : {9, 4, 6}) db.derive(0, d, std::vector<Value>{I(v)}.data());
  std::vector<Value> args{I(-3),
                          F(1.2346e+05),
                          Value::fromBool(true),
                          N(3),
                          Value::fromThread(1),
                          s.heap.makeString("abc"),
                          s.heap.makeList(li, std::vector<Value>{I(1), I(2), I(3)}),
                          s.heap.makeTuple(st, std::vector<Value>{I(1), F(0.5)}),
                          s.heap.makeTuple(ar, std::vector<Value>{I(0), I(4), I(0)}),
                          s.heap.makeTuple(se, std::vector<Value>{N(1), N(2), N(1)})};
  db.addLinear(0, all, args.data());
  const std::string expected =
      "0\nall(-3, 1.2346e+05, true, @3, #T1, \"abc\", [1,2,3], :(1, 0.5), #[0, 4, 0], {@1, @2})\n!dist(4)\n";
  BOOST_TEST(dumpDatabase(db) == expected);
  std::ostringstream os;
  dumpDatabase(os, db);
  BOOST_TEST(os.str() == expected);
}
