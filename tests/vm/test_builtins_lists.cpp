#define BOOST_TEST_MODULE vm_builtins_lists
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "builtins_fixture.hpp"

using namespace bitest;

BOOST_FIXTURE_TEST_SUITE(lists, Fix)

BOOST_AUTO_TEST_CASE(lnth_and_its_range_errors) {
  const Value l = ints({7, 8, 9});
  BOOST_CHECK_EQUAL(call("lnth", {l, I(0)}, tInt).asInt(), 7);
  BOOST_CHECK_EQUAL(call("lnth", {l, I(2)}, tInt).asInt(), 9);
  BOOST_CHECK_THROW(call("lnth", {l, I(3)}, tInt), RuntimeError);
  BOOST_CHECK_THROW(call("lnth", {l, I(-1)}, tInt), RuntimeError);
  BOOST_CHECK_THROW(call("lnth", {Value::nil(), I(0)}, tInt), RuntimeError);
  try {
    call("lnth", {l, I(5)}, tInt);
    BOOST_FAIL("no error");
  } catch (const RuntimeError& e) {
    BOOST_CHECK_EQUAL(std::string(e.what()), "lnth: index 5 out of range for a list of 3 elements");
  }
  // A boxed element comes back as a new reference (released by the fixture).
  BOOST_CHECK_EQUAL(show("lnth", {strs({"a", "bc"}), I(1)}, tString), "\"bc\"");
}

BOOST_AUTO_TEST_CASE(llength_llast) {
  BOOST_CHECK_EQUAL(call("llength", {Value::nil()}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("llength", {ints({1, 2, 3})}, tInt).asInt(), 3);
  BOOST_CHECK_EQUAL(call("llast", {ints({1, 2, 3})}, tInt).asInt(), 3);
  BOOST_CHECK_EQUAL(call("llast", {nodes({4})}, tNode).asNode(), 4u);
  BOOST_CHECK_THROW(call("llast", {Value::nil()}, tInt), RuntimeError);
}

BOOST_AUTO_TEST_CASE(lappend_copies_the_first_and_shares_the_second) {
  const Value a = ints({1, 2}), b = ints({3});
  const Value r = call("lappend", {a, b}, tLI);
  BOOST_CHECK_EQUAL(text(tLI, r), "[1,2,3]");
  BOOST_CHECK_EQUAL(listTail(listTail(r)).bits(), b.bits());
  BOOST_CHECK_EQUAL(text(tLI, a), "[1,2]");
  BOOST_CHECK_EQUAL(show("lappend", {Value::nil(), b}, tLI), "[3]");
  BOOST_CHECK_EQUAL(show("lappend", {a, Value::nil()}, tLI), "[1,2]");
  BOOST_CHECK_EQUAL(show("lappend", {Value::nil(), Value::nil()}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("lappend", {strs({"x"}), strs({"y", "z"})}, tLS), "[\"x\",\"y\",\"z\"]");
}

BOOST_AUTO_TEST_CASE(lreverse_values) {
  BOOST_CHECK_EQUAL(show("lreverse", {ints({1, 2, 3})}, tLI), "[3,2,1]");
  BOOST_CHECK_EQUAL(show("lreverse", {ints({-4})}, tLI), "[-4]");
  BOOST_CHECK_EQUAL(show("lreverse", {Value::nil()}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("lreverse", {nodes({1, 0})}, tLN), "[@0,@1]");
}

BOOST_AUTO_TEST_CASE(lsort_ints_floats_and_the_node_quirk) {
  BOOST_CHECK_EQUAL(show("lsort", {ints({3, -1, 2, -1})}, tLI), "[-1,-1,2,3]");
  BOOST_CHECK_EQUAL(show("lsort", {floats({2.5, -0.5, 1})}, tLF), "[-0.5,1,2.5]");
  BOOST_CHECK_EQUAL(show("lsort", {Value::nil()}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("lsort", {nodes({2, 0, 1})}, tLN), "[]");  // [quirk]
  BOOST_CHECK_EQUAL(show("lsort", {floats({std::nan(""), 1, -1})}, tLF), "[-1,1,nan]");
  BOOST_CHECK_EQUAL(show("lsort", {ints({2147483647, -2147483647 - 1, 0})}, tLI),
                    "[-2147483648,0,2147483647]");
}

BOOST_AUTO_TEST_CASE(lremove_all_occurrences) {
  BOOST_CHECK_EQUAL(show("lremove", {ints({1, 2, 1, 3}), I(1)}, tLI), "[2,3]");
  BOOST_CHECK_EQUAL(show("lremove", {ints({1, 2}), I(5)}, tLI), "[1,2]");
  BOOST_CHECK_EQUAL(show("lremove", {ints({4, 4}), I(4)}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("lremove", {Value::nil(), I(4)}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("lremove", {nodes({1, 2, 1}), N(1)}, tLN), "[@2]");
}

BOOST_AUTO_TEST_CASE(lremoveduplicates_in_hash_set_order) {
  // libstdc++ unordered_set<int>, 13 buckets: a value in a new bucket goes to the front of the
  // iteration order, one in an occupied bucket in front of that bucket's first node.
  BOOST_CHECK_EQUAL(show("lremoveduplicates", {ints({3, 1, 3, 2})}, tLI), "[2,1,3]");
  BOOST_CHECK_EQUAL(show("lremoveduplicates", {ints({5, -1, 20, 5, 7})}, tLI), "[7,20,-1,5]");
  BOOST_CHECK_EQUAL(show("lremoveduplicates", {Value::nil()}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("lremoveduplicates", {nodes({2, 1, 2})}, tLN), "[@2,@1]");
}

BOOST_AUTO_TEST_CASE(lcount_lexists_lexistss) {
  BOOST_CHECK_EQUAL(call("lcount", {ints({1, 2, 1}), I(1)}, tInt).asInt(), 2);
  BOOST_CHECK_EQUAL(call("lcount", {ints({1, 2, 1}), I(3)}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("lcount", {Value::nil(), I(1)}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("lcount", {strs({"a", "b", "a"}), str("a")}, tInt).asInt(), 2);
  BOOST_CHECK(call("lexists", {ints({1, 2}), I(2)}, tBool).asBool());
  BOOST_CHECK(!call("lexists", {ints({1, 2}), I(3)}, tBool).asBool());
  BOOST_CHECK(!call("lexists", {Value::nil(), I(1)}, tBool).asBool());
  BOOST_CHECK(call("lexists", {nodes({0, 5}), N(5)}, tBool).asBool());
  BOOST_CHECK(call("lexistss", {ints({1, 2}), ints({5, 2})}, tBool).asBool());
  BOOST_CHECK(!call("lexistss", {ints({1, 2}), ints({5})}, tBool).asBool());
  BOOST_CHECK(!call("lexistss", {Value::nil(), ints({1})}, tBool).asBool());
  BOOST_CHECK(!call("lexistss", {ints({1}), Value::nil()}, tBool).asBool());
}

BOOST_AUTO_TEST_CASE(ltake_quirk) {
  const Value l = ints({1, 2, 3});
  BOOST_CHECK_EQUAL(show("ltake", {l, I(2)}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("ltake", {l, I(1)}, tLI), "[]");
  const Value same = call("ltake", {l, I(0)}, tLI);
  BOOST_CHECK_EQUAL(same.bits(), l.bits());
  BOOST_CHECK_EQUAL(show("ltake", {l, I(-1)}, tLI), "[1,2,3]");
  BOOST_CHECK_EQUAL(show("ltake", {Value::nil(), I(0)}, tLI), "[]");
}

BOOST_AUTO_TEST_CASE(intlistdiff_intlistsub_intlistequal) {
  BOOST_CHECK_EQUAL(show("intlistdiff", {ints({1, 2, 3, 2, 4}), ints({2, 4})}, tLI), "[1,3]");
  BOOST_CHECK_EQUAL(show("intlistdiff", {ints({1, 1}), Value::nil()}, tLI), "[1,1]");
  BOOST_CHECK_EQUAL(show("intlistdiff", {Value::nil(), ints({1})}, tLI), "[]");
  const Value l = ints({10, 20, 30, 40});
  BOOST_CHECK_EQUAL(show("intlistsub", {l, I(1), I(3)}, tLI), "[20,30]");
  BOOST_CHECK_EQUAL(show("intlistsub", {l, I(0), I(10)}, tLI), "[10,20,30,40]");
  BOOST_CHECK_EQUAL(show("intlistsub", {l, I(-2), I(1)}, tLI), "[10]");
  BOOST_CHECK_EQUAL(show("intlistsub", {l, I(3), I(1)}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("intlistsub", {l, I(2), I(2)}, tLI), "[]");
  BOOST_CHECK_EQUAL(call("intlistequal", {ints({1, 2}), ints({1, 2})}, tInt).asInt(), 1);
  BOOST_CHECK_EQUAL(call("intlistequal", {ints({1, 2}), ints({1})}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("intlistequal", {ints({1}), ints({1, 2})}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("intlistequal", {ints({1, 2}), ints({1, 3})}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("intlistequal", {Value::nil(), Value::nil()}, tInt).asInt(), 1);
}

BOOST_AUTO_TEST_CASE(queens_violation_rows_and_diagonals) {
  // cols: rows of the queens already placed, nearest column first.
  BOOST_CHECK(!call("queens_violation", {I(2), ints({0})}, tBool).asBool());
  BOOST_CHECK(call("queens_violation", {I(1), ints({0})}, tBool).asBool());  // diagonal
  BOOST_CHECK(call("queens_violation", {I(0), ints({0})}, tBool).asBool());  // same row
  BOOST_CHECK(!call("queens_violation", {I(3), ints({1, 0})}, tBool).asBool());
  BOOST_CHECK(call("queens_violation", {I(2), ints({1, 0})}, tBool).asBool());  // d=1 diagonal
  BOOST_CHECK(call("queens_violation", {I(2), ints({4, 0})}, tBool).asBool());  // d=2 diagonal
  BOOST_CHECK(!call("queens_violation", {I(4), ints({2, 0})}, tBool).asBool());
  BOOST_CHECK(!call("queens_violation", {I(5), Value::nil()}, tBool).asBool());
}

BOOST_AUTO_TEST_SUITE_END()
