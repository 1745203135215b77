// Lists that keep sharing their tails across the facts of one batch between shards
// (fact_codec.hpp: ListEncoderShare / ListDecoderShare), as n-queens' placements do at `meld -j N`.
#define BOOST_TEST_MODULE vm_list_sharing
#include <boost/test/unit_test.hpp>

#include "meldvm/fact_codec.hpp"
#include "meldvm/value_ops.hpp"
#include "vm_fixture.hpp"

using namespace vmtest;

namespace {

// A sender's heap and a receiver's heap over the same types; p(list int) and q(list list int).
struct Shards {
  Store s;
  Heap receiver{s.types};
  TypeId li = s.types.list(TypeTable::kInt);
  TypeId lli = s.types.list(li);
  PredId p = s.linear("p", {li});
  PredId q = s.linear("q", {lli});

  Value list(std::vector<std::int32_t> items, Value tail = Value::nil()) {
    std::vector<Value> v;
    for (std::int32_t i : items) v.push_back(I(i));
    return s.heap.makeList(li, v, tail);
  }
  std::string text(TypeId t, Value v) const {
    std::string out;
    appendValue(out, s.types, t, v);
    return out;
  }
  // Decodes the facts of `bytes` (each prefixed by its u32 length) into the receiver's heap.
  std::vector<Value> decodeAll(const std::vector<std::vector<std::uint8_t>>& facts, ListDecoderShare& share) {
    std::vector<Value> out;
    DecodedFact d;
    for (const auto& f : facts) {
      decodeFact(f.data(), f.size(), s.preds, receiver, d, &share);
      out.push_back(d.args[0]);
    }
    return out;
  }
};

const void* cell(Value v) { return v.asObject(); }

}  // namespace

BOOST_AUTO_TEST_CASE(facts_consed_on_one_tail_share_it_after_the_trip) {
  Shards t;
  const Value tail = t.list({5, 6, 7, 8});
  const Value a = t.list({1}, tail), b = t.list({2}, tail), c = t.list({3}, tail);
  ListEncoderShare out(t.s.heap);
  std::vector<std::vector<std::uint8_t>> facts(3);
  encodeFact(facts[0], t.s.preds, t.p, &a, false, &out);
  encodeFact(facts[1], t.s.preds, t.p, &b, false, &out);
  encodeFact(facts[2], t.s.preds, t.p, &c, false, &out);
  // Header 3; the first list whole: count 4 + 5 ints + the end 4; the others: one cell and a reference.
  BOOST_TEST(facts[0].size() == 3u + 4 + 5 * 4 + 4);
  BOOST_TEST(facts[1].size() == 3u + 4 + 4 + 4);
  std::vector<std::uint8_t> plain;
  encodeFact(plain, t.s.preds, t.p, &b, false);
  BOOST_TEST(plain.size() == 3u + 4 + 5 * 4);

  ListDecoderShare in(t.receiver);
  const std::vector<Value> got = t.decodeAll(facts, in);
  BOOST_TEST(t.text(t.li, got[0]) == "[1,5,6,7,8]");
  BOOST_TEST(t.text(t.li, got[1]) == "[2,5,6,7,8]");
  BOOST_TEST(t.text(t.li, got[2]) == "[3,5,6,7,8]");
  BOOST_TEST(cell(listTail(got[1])) == cell(listTail(got[0])));
  BOOST_TEST(cell(listTail(got[2])) == cell(listTail(got[0])));
  // 5 + 1 + 1 cells, not 15.
  BOOST_TEST(t.receiver.liveObjects() == 7u);

  // Once the batch ends, both sides hold nothing: the receiver's lists live on their own
  // references, the sender's cells go when their facts do.
  in.reset();
  out.reset();
  for (Value v : got) t.receiver.release(t.li, v);
  BOOST_TEST(t.receiver.liveObjects() == 0u);
  for (Value v : {a, b, c, tail}) t.s.heap.release(t.li, v);
  BOOST_TEST(t.s.heap.liveObjects() == 0u);
}

BOOST_AUTO_TEST_CASE(the_encoder_holds_what_it_sent_so_an_address_is_never_reused_within_a_batch) {
  Shards t;
  ListEncoderShare out(t.s.heap);
  Value a = t.list({1, 2});
  std::vector<std::vector<std::uint8_t>> facts(2);
  encodeFact(facts[0], t.s.preds, t.p, &a, false, &out);
  const void* sent = cell(a);
  t.s.heap.release(t.li, a);                 // the fact is consumed on the sender
  BOOST_TEST(t.s.heap.liveObjects() == 2u);  // still held by the batch
  const Value b = t.list({3, 4});
  BOOST_TEST(cell(b) != sent);
  encodeFact(facts[1], t.s.preds, t.p, &b, false, &out);
  ListDecoderShare in(t.receiver);
  const std::vector<Value> got = t.decodeAll(facts, in);
  BOOST_TEST(t.text(t.li, got[1]) == "[3,4]");
  out.reset();
  BOOST_TEST(t.s.heap.liveObjects() == 2u);  // b's cells only
  t.s.heap.release(t.li, b);
  in.reset();
  for (Value v : got) t.receiver.release(t.li, v);
  BOOST_TEST(t.receiver.liveObjects() == 0u);
}

BOOST_AUTO_TEST_CASE(lists_of_lists_share_at_both_levels) {
  Shards t;
  const Value inner = t.list({1, 2});
  const Value outerTail = t.s.heap.makeList(t.lli, std::vector<Value>{inner});
  const Value x = t.s.heap.makeList(t.lli, std::vector<Value>{inner}, outerTail);
  const Value y = t.s.heap.makeList(t.lli, std::vector<Value>{inner}, outerTail);
  ListEncoderShare out(t.s.heap);
  std::vector<std::vector<std::uint8_t>> facts(2);
  encodeFact(facts[0], t.s.preds, t.q, &x, false, &out);
  encodeFact(facts[1], t.s.preds, t.q, &y, false, &out);
  ListDecoderShare in(t.receiver);
  const std::vector<Value> got = t.decodeAll(facts, in);
  BOOST_TEST(t.text(t.lli, got[0]) == "[[1,2],[1,2]]");
  BOOST_TEST(t.text(t.lli, got[1]) == "[[1,2],[1,2]]");
  BOOST_TEST(cell(listHead(got[0])) == cell(listHead(got[1])));  // one [1,2] for all four
  BOOST_TEST(cell(listTail(got[0])) == cell(listTail(got[1])));
  BOOST_TEST(t.receiver.liveObjects() == 2u + 1 + 2);  // [1,2], the shared outer cell, two heads
  in.reset();
  out.reset();
  for (Value v : got) t.receiver.release(t.lli, v);
  BOOST_TEST(t.receiver.liveObjects() == 0u);
  for (Value v : {x, y, outerTail}) t.s.heap.release(t.lli, v);
  t.s.heap.release(t.li, inner);
  BOOST_TEST(t.s.heap.liveObjects() == 0u);
}

BOOST_AUTO_TEST_CASE(a_reference_to_a_cell_not_sent_is_rejected_without_leaking) {
  Shards t;
  const Value tail = t.list({5});
  const Value a = t.list({1}, tail), b = t.list({2}, tail);
  ListEncoderShare out(t.s.heap);
  std::vector<std::vector<std::uint8_t>> facts(2);
  encodeFact(facts[0], t.s.preds, t.p, &a, false, &out);
  encodeFact(facts[1], t.s.preds, t.p, &b, false, &out);
  DecodedFact d;
  {
    ListDecoderShare fresh(t.receiver);  // the second fact alone: its reference points nowhere
    BOOST_CHECK_THROW(decodeFact(facts[1].data(), facts[1].size(), t.s.preds, t.receiver, d, &fresh),
                      FactCodecError);
  }
  BOOST_TEST(t.receiver.liveObjects() == 0u);
  for (std::size_t n = 0; n < facts[0].size(); ++n) {  // every truncation of the first
    ListDecoderShare in(t.receiver);
    BOOST_CHECK_THROW(decodeFact(facts[0].data(), n, t.s.preds, t.receiver, d, &in), FactCodecError);
  }
  BOOST_TEST(t.receiver.liveObjects() == 0u);
  out.reset();
  for (Value v : {a, b, tail}) t.s.heap.release(t.li, v);
  BOOST_TEST(t.s.heap.liveObjects() == 0u);
}

BOOST_AUTO_TEST_CASE(a_new_batch_shares_nothing_with_the_last_one) {
  Shards t;
  const Value tail = t.list({5, 6});
  const Value a = t.list({1}, tail), b = t.list({2}, tail);
  ListEncoderShare out(t.s.heap);
  std::vector<std::uint8_t> first, second;
  encodeFact(first, t.s.preds, t.p, &a, false, &out);
  out.reset();
  encodeFact(second, t.s.preds, t.p, &b, false, &out);
  BOOST_TEST(second.size() == first.size());  // b's tail goes whole again
  ListDecoderShare in(t.receiver);
  const std::vector<Value> got = t.decodeAll({first, second}, in);
  BOOST_TEST(t.text(t.li, got[1]) == "[2,5,6]");
  BOOST_TEST(cell(listTail(got[1])) != cell(listTail(got[0])));
  in.reset();
  out.reset();
  for (Value v : got) t.receiver.release(t.li, v);
  for (Value v : {a, b, tail}) t.s.heap.release(t.li, v);
  BOOST_TEST(t.receiver.liveObjects() == 0u);
  BOOST_TEST(t.s.heap.liveObjects() == 0u);
}

BOOST_AUTO_TEST_CASE(the_cell_numbers_grow_and_empty_without_confusing_batches) {
  Shards t;
  ListEncoderShare out(t.s.heap);
  std::vector<Value> lists;
  for (int round = 0; round < 3; ++round) {
    Value l = Value::nil();
    std::vector<std::vector<std::uint8_t>> facts;
    for (int i = 0; i < 500; ++i) {  // each list one cell longer than the last: 500 references
      const Value next = t.s.heap.cons(t.li, I(i), l);
      t.s.heap.release(t.li, l);
      l = next;
      facts.emplace_back();
      encodeFact(facts.back(), t.s.preds, t.p, &l, false, &out);
      // One new cell, then the end (the first list) or a reference (every later one).
      BOOST_TEST(facts.back().size() == 3u + 4 + 4 + 4);
    }
    ListDecoderShare in(t.receiver);
    const std::vector<Value> got = t.decodeAll(facts, in);
    BOOST_TEST(t.text(t.li, got[2]) == "[2,1,0]");
    BOOST_TEST(cell(listTail(got[499])) == cell(got[498]));
    in.reset();
    out.reset();
    for (Value v : got) t.receiver.release(t.li, v);
    t.s.heap.release(t.li, l);
  }
  BOOST_TEST(t.receiver.liveObjects() == 0u);
  BOOST_TEST(t.s.heap.liveObjects() == 0u);
}
