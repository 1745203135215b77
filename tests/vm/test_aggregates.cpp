// Aggregated persistent predicates (spec §4.1.2, §6.8): eager recomputation per group, retraction
// of the old value and assertion of the new one, inputs as a multiset, trailing fields from the
// winning (min/max) or first (first/sum) input.
#define BOOST_TEST_MODULE vm_aggregates
#include <boost/test/unit_test.hpp>

#include "vm_fixture.hpp"

using namespace vmtest;

namespace {

std::string text(Store& s, PredId p, std::span<const Value> args) {
  std::string out;
  appendFact(out, *s.db, p, args.data());
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(min_is_eager_with_retraction) {
  Store s;
  // type route dist(node, min int, node via): grouped by the home only.
  const PredId d = s.aggregate("dist", {TypeTable::kInt, TypeTable::kNode}, AggregateKind::Min, 0);
  Database& db = s.open(2);
  Change c = db.derive(0, d, std::vector<Value>{I(5), N(1)}.data());
  BOOST_TEST(c.added);
  BOOST_TEST(!c.removed);
  BOOST_TEST(text(s, d, c.addedArgs) == "!dist(5, @1)");
  c = db.derive(0, d, std::vector<Value>{I(7), N(1)}.data());  // worse: nothing visible changes
  BOOST_TEST(!c.added);
  BOOST_TEST(!c.removed);
  c = db.derive(0, d, std::vector<Value>{I(3), N(0)}.data());
  BOOST_TEST(c.removed);
  BOOST_TEST(c.added);
  BOOST_TEST(text(s, d, c.removedArgs) == "!dist(5, @1)");
  BOOST_TEST(text(s, d, c.addedArgs) == "!dist(3, @0)");
  BOOST_TEST(s.facts(0, d) == S({"!dist(3, @0)"}), boost::test_tools::per_element());
  BOOST_TEST(db.aggregateInputs(0, d) == 3u);
  BOOST_TEST(db.factCount(1, d) == 0u);

  // A tie keeps the earlier input (and its trailing field).
  c = db.derive(0, d, std::vector<Value>{I(3), N(1)}.data());
  BOOST_TEST(!c.added);
  // Retracting the winner publishes the next best; the tie's other input now wins.
  c = db.retract(0, d, std::vector<Value>{I(3), N(0)}.data());
  BOOST_TEST(c.found);
  BOOST_TEST(c.removed);
  BOOST_TEST(text(s, d, c.removedArgs) == "!dist(3, @0)");
  BOOST_TEST(text(s, d, c.addedArgs) == "!dist(3, @1)");
  db.retract(0, d, std::vector<Value>{I(3), N(1)}.data());
  BOOST_TEST(s.facts(0, d) == S({"!dist(5, @1)"}), boost::test_tools::per_element());
  // An input derived twice must be retracted twice.
  db.derive(0, d, std::vector<Value>{I(1), N(1)}.data());
  db.derive(0, d, std::vector<Value>{I(1), N(1)}.data());
  c = db.retract(0, d, std::vector<Value>{I(1), N(1)}.data());
  BOOST_TEST(!c.removed);
  BOOST_TEST(c.count == 1u);
  BOOST_TEST(s.facts(0, d) == S({"!dist(1, @1)"}), boost::test_tools::per_element());
  db.retract(0, d, std::vector<Value>{I(1), N(1)}.data());
  db.retract(0, d, std::vector<Value>{I(5), N(1)}.data());
  c = db.retract(0, d, std::vector<Value>{I(7), N(1)}.data());
  BOOST_TEST(c.removed);
  BOOST_TEST(!c.added);  // the group is empty: no fact at all
  BOOST_TEST(db.factCount(0, d) == 0u);
  BOOST_TEST(db.aggregateInputs(0, d) == 0u);
  BOOST_TEST(!db.retract(0, d, std::vector<Value>{I(7), N(1)}.data()).found);
}

BOOST_AUTO_TEST_CASE(groups_are_the_fields_before_the_aggregate) {
  Store s;
  // type best(node, node Key, max float, int Tag).
  const PredId b =
      s.aggregate("best", {TypeTable::kNode, TypeTable::kFloat, TypeTable::kInt}, AggregateKind::Max, 1);
  Database& db = s.open(2);
  db.derive(0, b, std::vector<Value>{N(1), F(1.5), I(10)}.data());
  db.derive(0, b, std::vector<Value>{N(2), F(0.5), I(20)}.data());
  db.derive(0, b, std::vector<Value>{N(1), F(2.5), I(30)}.data());
  db.derive(0, b, std::vector<Value>{N(2), F(-1.0), I(40)}.data());
  db.derive(1, b, std::vector<Value>{N(1), F(9.0), I(50)}.data());
  BOOST_TEST(s.facts(0, b) == S({"!best(@2, 0.5, 20)", "!best(@1, 2.5, 30)"}),
             boost::test_tools::per_element());
  BOOST_TEST(s.facts(1, b) == S({"!best(@1, 9, 50)"}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(sum_counts_every_copy_and_first_keeps_the_first) {
  Store s;
  const PredId si = s.aggregate("total", {TypeTable::kInt, TypeTable::kInt}, AggregateKind::Sum, 0);
  const PredId sf = s.aggregate("mass", {TypeTable::kFloat}, AggregateKind::Sum, 0);
  const PredId fi = s.aggregate("firstone", {TypeTable::kInt, TypeTable::kInt}, AggregateKind::First, 0);
  Database& db = s.open(1);
  db.derive(0, si, std::vector<Value>{I(4), I(1)}.data());
  db.derive(0, si, std::vector<Value>{I(4), I(1)}.data());  // a second copy counts
  Change c = db.derive(0, si, std::vector<Value>{I(10), I(2)}.data());
  BOOST_TEST(text(s, si, c.removedArgs) == "!total(8, 1)");
  BOOST_TEST(text(s, si, c.addedArgs) == "!total(18, 1)");  // trailing field from the first input
  c = db.retract(0, si, std::vector<Value>{I(4), I(1)}.data());
  BOOST_TEST(text(s, si, c.addedArgs) == "!total(14, 1)");
  db.retract(0, si, std::vector<Value>{I(4), I(1)}.data());
  BOOST_TEST(s.facts(0, si) == S({"!total(10, 2)"}), boost::test_tools::per_element());
  // An input that leaves the sum unchanged publishes nothing.
  c = db.derive(0, si, std::vector<Value>{I(0), I(2)}.data());
  BOOST_TEST(!c.added);
  BOOST_TEST(!c.removed);

  db.derive(0, sf, std::vector<Value>{F(0.25)}.data());
  db.derive(0, sf, std::vector<Value>{F(1.5)}.data(), 2);
  BOOST_TEST(s.facts(0, sf) == S({"!mass(3.25)"}), boost::test_tools::per_element());

  db.derive(0, fi, std::vector<Value>{I(7), I(1)}.data());
  db.derive(0, fi, std::vector<Value>{I(3), I(2)}.data());
  BOOST_TEST(s.facts(0, fi) == S({"!firstone(7, 1)"}), boost::test_tools::per_element());
  c = db.retract(0, fi, std::vector<Value>{I(7), I(1)}.data());
  BOOST_TEST(text(s, fi, c.addedArgs) == "!firstone(3, 2)");
}

BOOST_AUTO_TEST_CASE(sum_of_float_lists_is_element_wise) {
  Store s;
  const TypeId lf = s.types.list(TypeTable::kFloat);
  const PredId v = s.aggregate("vec", {TypeTable::kInt, lf}, AggregateKind::Sum, 1);
  Database& db = s.open(1);
  Value a = s.heap.makeList(lf, std::vector<Value>{F(1), F(2), F(3)});
  Value b = s.heap.makeList(lf, std::vector<Value>{F(0.5), F(0.25)});
  db.derive(0, v, std::vector<Value>{I(1), a}.data());
  BOOST_TEST(s.facts(0, v) == S({"!vec(1, [1,2,3])"}), boost::test_tools::per_element());
  db.derive(0, v, std::vector<Value>{I(1), b}.data());
  BOOST_TEST(s.facts(0, v) == S({"!vec(1, [1.5,2.25])"}),
             boost::test_tools::per_element());  // the shorter length
  db.derive(0, v, std::vector<Value>{I(2), b}.data());
  BOOST_TEST(s.facts(0, v) == S({"!vec(1, [1.5,2.25])", "!vec(2, [0.5,0.25])"}),
             boost::test_tools::per_element());
  db.retract(0, v, std::vector<Value>{I(1), a}.data());
  db.retract(0, v, std::vector<Value>{I(1), b}.data());
  db.retract(0, v, std::vector<Value>{I(2), b}.data());
  db.derive(0, v, std::vector<Value>{I(3), Value::nil()}.data());  // flush the last change's scratch
  s.heap.release(lf, a);
  s.heap.release(lf, b);
  BOOST_TEST(s.facts(0, v) == S({"!vec(3, [])"}), boost::test_tools::per_element());
  BOOST_TEST(s.heap.liveObjects() == 0u);  // no list cell leaked by the sums
}

// `type p(node, min int)` / `max int`: the input is the value itself (the store's int fast path),
// with the same outcome as the general case: counts, retraction of the winner, an emptied group.
BOOST_AUTO_TEST_CASE(single_int_min_and_max) {
  Store s;
  const PredId lo = s.aggregate("lo", {TypeTable::kInt}, AggregateKind::Min, 0);
  const PredId hi = s.aggregate("hi", {TypeTable::kInt}, AggregateKind::Max, 0);
  Database& db = s.open(2);
  for (int v : {5, 3, 8, 3}) {
    db.derive(1, lo, std::vector<Value>{I(v)}.data());
    db.derive(1, hi, std::vector<Value>{I(v)}.data());
  }
  BOOST_TEST(s.facts(1, lo) == S({"!lo(3)"}), boost::test_tools::per_element());
  BOOST_TEST(s.facts(1, hi) == S({"!hi(8)"}), boost::test_tools::per_element());
  BOOST_TEST(db.aggregateInputs(1, lo) == 3u);
  BOOST_TEST(db.factCount(0, lo) == 0u);
  // 3 was derived twice: the first retraction only lowers its count.
  Change c = db.retract(1, lo, std::vector<Value>{I(3)}.data());
  BOOST_TEST(!c.removed);
  BOOST_TEST(c.count == 1u);
  c = db.retract(1, lo, std::vector<Value>{I(3)}.data());
  BOOST_TEST(c.removed);
  BOOST_TEST(c.added);
  BOOST_TEST(text(s, lo, c.removedArgs) == "!lo(3)");
  BOOST_TEST(text(s, lo, c.addedArgs) == "!lo(5)");
  c = db.retract(1, lo, std::vector<Value>{I(8)}.data());  // not the winner: nothing visible
  BOOST_TEST(!c.removed);
  BOOST_TEST(!c.added);
  c = db.derive(1, lo, std::vector<Value>{I(5)}.data());  // a second copy of the winner
  BOOST_TEST(!c.added);
  BOOST_TEST(c.count == 2u);
  c = db.retract(1, hi, std::vector<Value>{I(8)}.data());
  BOOST_TEST(text(s, hi, c.addedArgs) == "!hi(5)");
  BOOST_TEST(!db.retract(1, hi, std::vector<Value>{I(4)}.data()).found);
  db.retract(1, hi, std::vector<Value>{I(5)}.data());
  db.retract(1, hi, std::vector<Value>{I(3)}.data());
  c = db.retract(1, hi, std::vector<Value>{I(3)}.data());
  BOOST_TEST(c.removed);
  BOOST_TEST(!c.added);
  BOOST_TEST(db.factCount(1, hi) == 0u);
  BOOST_TEST(db.aggregateInputs(1, hi) == 0u);
}
