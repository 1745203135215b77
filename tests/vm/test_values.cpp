// Values: the type table, scalar encoding, reference-counted objects, equality/hash/order, and the
// dump text of every type (spec §3.1, §8).
#define BOOST_TEST_MODULE vm_values
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/value_ops.hpp"

using namespace meldvm;

namespace {

struct Env {
  TypeTable types;
  Heap heap{types};
  std::string text(TypeId t, Value v) {
    std::string s;
    appendValue(s, types, t, v);
    return s;
  }
};

std::string floatText(double d) {
  std::string s;
  appendFloat(s, d);
  return s;
}

}  // namespace

BOOST_AUTO_TEST_CASE(type_table_interns_and_names) {
  TypeTable t;
  BOOST_TEST((t.kind(TypeTable::kInt) == TypeKind::Int));
  BOOST_TEST((t.kind(TypeTable::kString) == TypeKind::String));
  const TypeId li = t.list(TypeTable::kInt);
  BOOST_TEST(t.list(TypeTable::kInt) == li);  // interned
  const TypeId lli = t.list(li);
  BOOST_TEST(lli != li);
  BOOST_TEST(t.element(lli) == li);
  const TypeId fields[] = {TypeTable::kInt, TypeTable::kFloat};
  const TypeId st = t.structOf(fields);
  BOOST_TEST(t.structOf(fields) == st);
  BOOST_TEST(t.fields(st).size() == 2u);
  BOOST_TEST(t.name(lli) == "list list int");
  BOOST_TEST(t.name(st) == ":(int, float)");
  BOOST_TEST(t.name(t.array(TypeTable::kNode)) == "array node");
  BOOST_TEST(t.name(t.set(TypeTable::kThread)) == "set thread");
  BOOST_TEST(!t.boxed(TypeTable::kNode));
  BOOST_TEST(t.boxed(TypeTable::kString));
  BOOST_TEST(t.boxed(li));
  BOOST_CHECK_THROW(t.list(999), std::out_of_range);
}

BOOST_AUTO_TEST_CASE(scalars_round_trip) {
  BOOST_TEST(Value::fromInt(-7).asInt() == -7);
  BOOST_TEST(Value::fromInt(std::numeric_limits<std::int32_t>::min()).asInt() ==
             std::numeric_limits<std::int32_t>::min());
  BOOST_TEST(Value::fromFloat(-0.40761).asFloat() == -0.40761);
  BOOST_TEST(Value::fromBool(true).asBool());
  BOOST_TEST(!Value::fromBool(false).asBool());
  BOOST_TEST(Value::fromNode(4000000000u).asNode() == 4000000000u);
  BOOST_TEST(Value::fromThread(3).asThread() == 3u);
  BOOST_TEST(Value::nil().isNil());
}

BOOST_AUTO_TEST_CASE(objects_are_counted_and_recycled) {
  Env e;
  const TypeId li = e.types.list(TypeTable::kInt);
  Value tail = e.heap.makeList(li, std::vector<Value>{Value::fromInt(2), Value::fromInt(3)});
  BOOST_TEST(e.heap.liveObjects() == 2u);
  Value a = e.heap.cons(li, Value::fromInt(1), tail);
  Value b = e.heap.cons(li, Value::fromInt(9), tail);  // shares the tail
  BOOST_TEST(e.heap.liveObjects() == 4u);
  e.heap.release(li, tail);  // still held by a and b
  BOOST_TEST(e.heap.liveObjects() == 4u);
  BOOST_TEST(e.text(li, a) == "[1,2,3]");
  BOOST_TEST(e.text(li, b) == "[9,2,3]");
  e.heap.release(li, a);
  BOOST_TEST(e.heap.liveObjects() == 3u);
  e.heap.release(li, b);
  BOOST_TEST(e.heap.liveObjects() == 0u);
  BOOST_TEST(e.heap.bytesInUse() == 0u);
  // A freed block is reused: no new slab.
  const std::size_t reserved = e.heap.bytesReserved();
  Value c = e.heap.makeList(li, std::vector<Value>{Value::fromInt(5)});
  BOOST_TEST(e.heap.bytesReserved() == reserved);
  e.heap.release(li, c);

  // Nested boxed values are released with their container; large objects too.
  const TypeId ls = e.types.list(TypeTable::kString);
  Value s = e.heap.makeString(std::string(2000, 'x'));
  Value l = e.heap.makeList(ls, std::vector<Value>{s, s});
  e.heap.release(TypeTable::kString, s);
  BOOST_TEST(e.heap.liveObjects() == 3u);
  e.heap.release(ls, l);
  BOOST_TEST(e.heap.liveObjects() == 0u);

  // Releasing a very long list does not recurse per cell.
  std::vector<Value> many(200000, Value::fromInt(1));
  Value big = e.heap.makeList(li, many);
  BOOST_TEST(e.heap.liveObjects() == 200000u);
  e.heap.release(li, big);
  BOOST_TEST(e.heap.liveObjects() == 0u);
}

// A dead cell's tail is dropped some deaths later (Heap::destroy puts it off): a tree of lists
// sharing their tails, as n-queens builds, released in random order, with lists inside structs
// (a death inside a death), must keep every live list whole and free every cell in the end.
BOOST_AUTO_TEST_CASE(deferred_tails_free_each_cell_once) {
  Env e;
  const TypeId li = e.types.list(TypeTable::kInt);
  const TypeId fields[] = {TypeTable::kInt, li};
  const TypeId st = e.types.structOf(fields);
  std::vector<Value> lists{Value::nil()};
  std::vector<std::string> texts{"[]"};
  for (int i = 0; i < 600; ++i) {  // each new list conses onto an earlier one
    const std::size_t parent = std::size_t(i * 7919) % lists.size();
    lists.push_back(e.heap.cons(li, Value::fromInt(i), lists[parent]));
    texts.push_back(e.text(li, lists.back()));
  }
  std::vector<std::pair<Value, std::size_t>> held;  // every third list also held by a struct
  for (std::size_t i = 1; i < lists.size(); i += 3)
    held.emplace_back(e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(0), lists[i]}), i);
  std::vector<std::size_t> order(lists.size() - 1);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i + 1;
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  std::vector<bool> released(lists.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    e.heap.release(li, lists[order[k]]);
    released[order[k]] = true;
    if (k % 50 == 0 && !held.empty()) {  // a struct dies: its list may die inside its death
      e.heap.release(st, held.back().first);
      held.pop_back();
    }
    if (k % 37 == 0)  // the lists still held read back whole
      for (std::size_t i = 1; i < lists.size(); ++i)
        if (!released[i]) BOOST_TEST(e.text(li, lists[i]) == texts[i]);
  }
  for (const auto& [tuple, i] : held) {
    BOOST_TEST(e.text(li, tupleItems(tuple)[1]) == texts[i]);
    e.heap.release(st, tuple);
  }
  BOOST_TEST(e.heap.liveObjects() == 0u);
  BOOST_TEST(e.heap.bytesInUse() == 0u);
}

BOOST_AUTO_TEST_CASE(equality_hash_and_order) {
  Env e;
  const TypeTable& t = e.types;
  const TypeId li = e.types.list(TypeTable::kInt);
  BOOST_TEST(valuesEqual(t, TypeTable::kFloat, Value::fromFloat(0.0), Value::fromFloat(-0.0)));
  BOOST_TEST(hashValue(t, TypeTable::kFloat, Value::fromFloat(0.0)) ==
             hashValue(t, TypeTable::kFloat, Value::fromFloat(-0.0)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(valuesEqual(t, TypeTable::kFloat, Value::fromFloat(nan), Value::fromFloat(nan)));
  BOOST_TEST(!valuesEqual(t, TypeTable::kInt, Value::fromInt(1), Value::fromInt(2)));

  Value s1 = e.heap.makeString("abc"), s2 = e.heap.makeString("abc"), s3 = e.heap.makeString("abd");
  BOOST_TEST(valuesEqual(t, TypeTable::kString, s1, s2));
  BOOST_TEST(hashValue(t, TypeTable::kString, s1) == hashValue(t, TypeTable::kString, s2));
  BOOST_TEST(!valuesEqual(t, TypeTable::kString, s1, s3));
  BOOST_TEST(compareValues(t, TypeTable::kString, s1, s3) < 0);

  Value l1 = e.heap.makeList(li, std::vector<Value>{Value::fromInt(1), Value::fromInt(2)});
  Value l2 = e.heap.makeList(li, std::vector<Value>{Value::fromInt(1), Value::fromInt(2)});
  Value l3 = e.heap.makeList(li, std::vector<Value>{Value::fromInt(1)});
  BOOST_TEST(valuesEqual(t, li, l1, l2));
  BOOST_TEST(hashValue(t, li, l1) == hashValue(t, li, l2));
  BOOST_TEST(!valuesEqual(t, li, l1, l3));
  BOOST_TEST(!valuesEqual(t, li, l1, Value::nil()));
  BOOST_TEST(valuesEqual(t, li, Value::nil(), Value::nil()));
  BOOST_TEST(compareValues(t, li, l3, l1) < 0);  // prefix first
  BOOST_TEST(compareValues(t, li, l1, l2) == 0);
  BOOST_TEST(compareValues(t, TypeTable::kInt, Value::fromInt(-5), Value::fromInt(3)) < 0);
  BOOST_TEST(compareValues(t, TypeTable::kFloat, Value::fromFloat(2.5), Value::fromFloat(-1.0)) > 0);
  BOOST_TEST(compareValues(t, TypeTable::kNode, Value::fromNode(2), Value::fromNode(10)) < 0);

  const TypeId fields[] = {TypeTable::kInt, TypeTable::kString};
  const TypeId st = e.types.structOf(fields);
  Value t1 = e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(1), s1});
  Value t2 = e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(1), s2});
  Value t3 = e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(1), s3});
  BOOST_TEST(valuesEqual(t, st, t1, t2));
  BOOST_TEST(hashValue(t, st, t1) == hashValue(t, st, t2));
  BOOST_TEST(!valuesEqual(t, st, t1, t3));
  BOOST_CHECK_THROW(e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(1)}), std::invalid_argument);

  for (Value v : {t1, t2, t3}) e.heap.release(st, v);
  for (Value v : {l1, l2, l3}) e.heap.release(li, v);
  for (Value v : {s1, s2, s3}) e.heap.release(TypeTable::kString, v);
  BOOST_TEST(e.heap.liveObjects() == 0u);
}

// A struct of unboxed items built in place equals the one makeTuple copies; a type whose items hold
// references, a set or a wrong field count is refused before anything is allocated.
BOOST_AUTO_TEST_CASE(plain_tuples_are_built_in_place) {
  Env e;
  const TypeId floats[] = {TypeTable::kFloat, TypeTable::kFloat, TypeTable::kFloat};
  const TypeId st = e.types.structOf(floats);
  Value built;
  Value* items = e.heap.makePlainTuple(st, 3, built);
  for (int i = 0; i < 3; ++i) items[i] = Value::fromFloat(0.5 * i - 1);
  const Value copied = e.heap.makeTuple(
      st, std::vector<Value>{Value::fromFloat(-1), Value::fromFloat(-0.5), Value::fromFloat(0)});
  BOOST_TEST(valuesEqual(e.types, st, built, copied));
  BOOST_TEST(e.text(st, built) == ":(-1, -0.5, 0)");
  BOOST_TEST(e.heap.liveObjects() == 2u);

  Value unused;
  const TypeId mixed[] = {TypeTable::kInt, TypeTable::kString};
  BOOST_CHECK_THROW(e.heap.makePlainTuple(e.types.structOf(mixed), 2, unused), std::invalid_argument);
  BOOST_CHECK_THROW(e.heap.makePlainTuple(st, 2, unused), std::invalid_argument);
  BOOST_CHECK_THROW(e.heap.makePlainTuple(e.types.set(TypeTable::kInt), 2, unused), std::invalid_argument);
  BOOST_TEST(e.heap.liveObjects() == 2u);

  // Once the type is known, the inline path builds the same object, and still refuses a wrong
  // field count; a dying plain struct (either builder's) gives its block back.
  Value again;
  Value* more = e.heap.makePlainTuple(st, 3, again);
  for (int i = 0; i < 3; ++i) more[i] = Value::fromFloat(0.5 * i - 1);
  BOOST_TEST(valuesEqual(e.types, st, again, copied));
  BOOST_CHECK_THROW(e.heap.makePlainTuple(st, 4, unused), std::invalid_argument);
  BOOST_TEST(e.heap.liveObjects() == 3u);
  for (Value v : {built, copied, again}) e.heap.release(st, v);
  BOOST_TEST(e.heap.liveObjects() == 0u);
  BOOST_TEST(e.heap.bytesInUse() == 0u);
}

// §8 table: float like printf("%.5g").
BOOST_AUTO_TEST_CASE(floats_print_like_percent_5g) {
  BOOST_TEST(floatText(2.5) == "2.5");
  BOOST_TEST(floatText(3.14) == "3.14");
  BOOST_TEST(floatText(2.0) == "2");
  BOOST_TEST(floatText(-0.40761) == "-0.40761");
  BOOST_TEST(floatText(-0.407612345) == "-0.40761");
  BOOST_TEST(floatText(0.00001) == "1e-05");
  BOOST_TEST(floatText(123456.0) == "1.2346e+05");
  BOOST_TEST(floatText(100000.0) == "1e+05");
  BOOST_TEST(floatText(99999.0) == "99999");
  BOOST_TEST(floatText(0.0001) == "0.0001");
  BOOST_TEST(floatText(3.140000104904175) == "3.14");  // a single-precision literal widened (§1.4)
  BOOST_TEST(floatText(std::numeric_limits<double>::infinity()) == "inf");
}

BOOST_AUTO_TEST_CASE(every_type_prints_as_in_the_dump_table) {
  Env e;
  BOOST_TEST(e.text(TypeTable::kInt, Value::fromInt(-3)) == "-3");
  BOOST_TEST(e.text(TypeTable::kBool, Value::fromBool(true)) == "true");
  BOOST_TEST(e.text(TypeTable::kBool, Value::fromBool(false)) == "false");
  BOOST_TEST(e.text(TypeTable::kNode, Value::fromNode(3)) == "@3");
  BOOST_TEST(e.text(TypeTable::kThread, Value::fromThread(0)) == "#T0");
  Value s = e.heap.makeString("a b\"c");
  BOOST_TEST(e.text(TypeTable::kString, s) == "\"a b\"c\"");  // raw, nothing escaped

  const TypeId li = e.types.list(TypeTable::kInt), lli = e.types.list(li);
  const TypeId ln = e.types.list(TypeTable::kNode), lf = e.types.list(TypeTable::kFloat);
  Value a = e.heap.makeList(li, std::vector<Value>{Value::fromInt(1), Value::fromInt(2)});
  Value b = e.heap.makeList(li, std::vector<Value>{Value::fromInt(3)});
  Value ab = e.heap.makeList(lli, std::vector<Value>{a, b});
  Value nodes = e.heap.makeList(ln, std::vector<Value>{Value::fromNode(1), Value::fromNode(0)});
  BOOST_TEST(e.text(li, a) == "[1,2]");
  BOOST_TEST(e.text(lli, ab) == "[[1,2],[3]]");
  BOOST_TEST(e.text(li, Value::nil()) == "[]");
  BOOST_TEST(e.text(ln, nodes) == "[@1,@0]");
  BOOST_TEST(e.text(e.types.list(TypeTable::kString),
                    e.heap.makeList(e.types.list(TypeTable::kString), std::vector<Value>{s})) ==
             "[\"a b\"c\"]");

  // Long lists are printed in full (§8: no "..." after the 21st element).
  std::vector<Value> items;
  std::string expected = "[";
  for (int i = 0; i < 25; ++i) {
    items.push_back(Value::fromFloat(i + 0.5));
    if (i) expected += ',';
    expected += std::to_string(i);
    expected += ".5";
  }
  expected += "]";
  Value longList = e.heap.makeList(lf, items);
  BOOST_TEST(e.text(lf, longList) == expected);

  const TypeId fields[] = {TypeTable::kInt, TypeTable::kInt};
  const TypeId st = e.types.structOf(fields);
  BOOST_TEST(e.text(st, e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(1), Value::fromInt(2)})) ==
             ":(1, 2)");
  const TypeId ar = e.types.array(TypeTable::kInt);
  BOOST_TEST(e.text(ar, e.heap.makeTuple(ar, std::vector<Value>{Value::fromInt(0), Value::fromInt(4),
                                                                Value::fromInt(0)})) == "#[0, 4, 0]");
  BOOST_TEST(e.text(ar, e.heap.makeTuple(ar, std::vector<Value>{})) == "#[]");
  const TypeId se = e.types.set(TypeTable::kInt);
  BOOST_TEST(e.text(se, e.heap.makeTuple(se, std::vector<Value>{Value::fromInt(1), Value::fromInt(2),
                                                                Value::fromInt(1)})) == "{1, 2}");
  // A list of structs: list commas without spaces, struct commas with.
  const TypeId lst = e.types.list(st);
  Value p = e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(1), Value::fromInt(2)});
  Value q = e.heap.makeTuple(st, std::vector<Value>{Value::fromInt(3), Value::fromInt(4)});
  BOOST_TEST(e.text(lst, e.heap.makeList(lst, std::vector<Value>{p, q})) == "[:(1, 2),:(3, 4)]");
  // (Values deliberately leaked here: the heap reclaims its slabs when it goes.)
}
