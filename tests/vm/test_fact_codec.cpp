// Facts as link messages (fact_codec.hpp): every value type survives the round trip, the size is
// the documented layout, malformed bytes are rejected without leaking.
#define BOOST_TEST_MODULE vm_fact_codec
#include <boost/test/unit_test.hpp>

#include "meldvm/fact_codec.hpp"
#include "meldvm/value_ops.hpp"
#include "vm_fixture.hpp"

using namespace vmtest;

namespace {

struct Codec {
  Store s;
  PredId p;
  std::vector<Value> args;
  Codec() {
    const TypeId li = s.types.list(TypeTable::kInt);
    const TypeId lli = s.types.list(li);
    const TypeId pair = s.types.structOf(std::vector<TypeId>{TypeTable::kInt, TypeTable::kString});
    const TypeId arr = s.types.array(TypeTable::kFloat);
    p = s.linear("all", {TypeTable::kInt, TypeTable::kFloat, TypeTable::kBool, TypeTable::kNode,
                         TypeTable::kString, lli, pair, arr});
    const Value l1 = s.heap.makeList(li, std::vector<Value>{I(1), I(2)});
    const Value l2 = s.heap.makeList(li, std::vector<Value>{I(3)});
    const Value str = s.heap.makeString("hi");
    args = {I(-7),
            F(2.5),
            Value::fromBool(true),
            N(9),
            s.heap.makeString("abc"),
            s.heap.makeList(lli, std::vector<Value>{l1, l2}),
            s.heap.makeTuple(pair, std::vector<Value>{I(4), str}),
            s.heap.makeTuple(arr, std::vector<Value>{F(0.5), F(-1)})};
    for (Value v : {l1, l2}) s.heap.release(li, v);
    s.heap.release(TypeTable::kString, str);
  }
  ~Codec() {
    for (std::size_t i = 0; i < args.size(); ++i) s.heap.release(s.preds[p].fields[i], args[i]);
  }
  std::string text(const std::vector<Value>& a) const {
    std::string out;
    for (std::size_t i = 0; i < a.size(); ++i)
      appendValue(out, s.types, s.preds[p].fields[i], a[i]), out += ' ';
    return out;
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(every_value_type_survives_the_round_trip) {
  Codec c;
  std::vector<std::uint8_t> bytes;
  encodeFact(bytes, c.s.preds, c.p, c.args.data(), true);
  // 2 + 1 header; int 4, float 8, bool 1, node 4, "abc" 4+3, [[1,2],[3]] 4+(4+8)+(4+4), :(4,"hi")
  // 4+4+2, #[0.5,-1] 4+16.
  BOOST_TEST(bytes.size() == 3u + 4 + 8 + 1 + 4 + 7 + 24 + 10 + 20);
  DecodedFact d;
  decodeFact(bytes.data(), bytes.size(), c.s.preds, c.s.heap, d);
  BOOST_TEST(d.pred == c.p);
  BOOST_TEST(d.negative);
  BOOST_TEST(c.text(d.args) == c.text(c.args));
  BOOST_TEST(c.text(d.args) == "-7 2.5 true @9 \"abc\" [[1,2],[3]] :(4, \"hi\") #[0.5, -1] ");
  for (std::size_t i = 0; i < d.args.size(); ++i) c.s.heap.release(c.s.preds[c.p].fields[i], d.args[i]);
}

BOOST_AUTO_TEST_CASE(malformed_messages_are_rejected_and_leak_nothing) {
  Codec c;
  std::vector<std::uint8_t> bytes;
  encodeFact(bytes, c.s.preds, c.p, c.args.data(), false);
  const std::size_t live = c.s.heap.liveObjects();
  DecodedFact d;
  for (std::size_t n = 0; n < bytes.size(); ++n)  // every truncation
    BOOST_CHECK_THROW(decodeFact(bytes.data(), n, c.s.preds, c.s.heap, d), FactCodecError);
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  BOOST_CHECK_THROW(decodeFact(longer.data(), longer.size(), c.s.preds, c.s.heap, d), FactCodecError);
  std::vector<std::uint8_t> badPred = bytes;
  badPred[0] = 0xFF;
  BOOST_CHECK_THROW(decodeFact(badPred.data(), badPred.size(), c.s.preds, c.s.heap, d), FactCodecError);
  BOOST_TEST(c.s.heap.liveObjects() == live);
}
