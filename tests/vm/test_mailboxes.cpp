// Mailboxes: messages come back in arrival order with the arguments they were posted with, narrow
// records (all 32-bit scalars) and mixed ones included, across chained chunks (a small one first,
// then big ones) and recycled chunks, and across the mailboxes of shards that share their chunks
// (MailSlabs).
#define BOOST_TEST_MODULE vm_mailboxes
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "meldvm/mailboxes.hpp"

using namespace meldvm;

namespace {

struct Message {
  PredId pred;
  bool negative;
  std::vector<std::uint64_t> bits;
  bool operator==(const Message&) const = default;
};

std::ostream& operator<<(std::ostream& os, const Message& m) {
  os << "p" << m.pred << (m.negative ? "-" : "+") << "(";
  for (std::uint64_t b : m.bits) os << std::hex << b << std::dec << ",";
  return os << ")";
}

const std::vector<std::vector<ArgWidth>> kShapes = {
    {},                                                     // 0: no argument
    {ArgWidth::Int32},                                      // 1: p(node, min int)
    {ArgWidth::Uint32, ArgWidth::Int32, ArgWidth::Uint32},  // 2: node, int, bool
    {ArgWidth::Word, ArgWidth::Int32},                      // 3: a float and an int: mixed
    std::vector<ArgWidth>(17, ArgWidth::Int32),             // 4: too wide to pack
    std::vector<ArgWidth>(16, ArgWidth::Int32),             // 5: the widest narrow record
    {ArgWidth::Uint32, ArgWidth::Word},                     // 6: node, float: two words
    // 7: the int waits in the half the first float skipped, the bool takes the next half
    {ArgWidth::Word, ArgWidth::Int32, ArgWidth::Word, ArgWidth::Uint32, ArgWidth::Int32},
    {ArgWidth::Word, ArgWidth::Word},  // 8: whole words
};
const std::vector<PredId> kAll = {0, 1, 2, 3, 4, 5, 6, 7, 8};

void post(Mailboxes& m, NodeId n, const Message& msg) {
  std::vector<Value> args;
  for (std::uint64_t b : msg.bits) args.push_back(Value::fromBits(b));
  m.post(n, msg.pred, msg.negative, args.data());
}

std::vector<Message> taken(const Mailboxes& m, NodeId n, const std::vector<PredId>& shown = kAll,
                           std::uint32_t maxChunks = Mailboxes::kAllChunks) {
  std::vector<Message> out;
  auto select = [&](PredId p) {
    for (PredId q : shown)
      if (p == q) return true;
    return false;
  };
  m.forEach(
      n, select,
      [&](PredId p, bool negative, const Value* args) {
        Message msg{p, negative, {}};
        for (std::size_t i = 0; i < kShapes[p].size(); ++i) msg.bits.push_back(args[i].bits());
        out.push_back(msg);
      },
      maxChunks);
  return out;
}

std::uint64_t I(int v) { return Value::fromInt(v).bits(); }

}  // namespace

BOOST_AUTO_TEST_CASE(every_shape_round_trips_in_arrival_order) {
  Mailboxes m(kShapes);
  m.addNodes(2);
  std::vector<std::uint64_t> wide(17), widest(16);
  for (int i = 0; i < 17; ++i) wide[i] = I(i % 2 ? -i : i * 1000);
  for (int i = 0; i < 16; ++i) widest[i] = I(i % 3 ? -70000 * i : 0x7FFFFFFF - i);
  const std::vector<Message> sent = {
      {0, false, {}},
      {1, false, {I(-1)}},
      {1, true, {I(2147483647)}},
      {1, false, {I(-2147483647 - 1)}},
      {2, false, {Value::fromNode(0xFFFFFFFEu).bits(), I(-5), Value::fromBool(true).bits()}},
      {2, true, {Value::fromNode(0).bits(), I(0), Value::fromBool(false).bits()}},
      {3, false, {Value::fromFloat(-0.25).bits(), I(-3)}},
      {4, true, wide},
      {5, false, widest},
      {6, false, {Value::fromNode(0xFFFFFFFEu).bits(), Value::fromFloat(1e300).bits()}},
      {7,
       true,
       {Value::fromFloat(-2.5).bits(), I(-2147483647 - 1), Value::fromBits(0xFFFFFFFFFFFFFFFFull).bits(),
        Value::fromBool(true).bits(), I(-1)}},
      {8, false, {Value::fromFloat(3.0).bits(), Value::fromBits(0x8000000000000001ull).bits()}},
      {6, true, {Value::fromNode(7).bits(), Value::fromFloat(-0.0).bits()}},
  };
  BOOST_TEST(m.empty(1));
  for (const Message& msg : sent) post(m, 1, msg);
  BOOST_TEST(m.empty(0));
  BOOST_TEST(!m.empty(1));
  BOOST_TEST(taken(m, 1) == sent, boost::test_tools::per_element());
  // Only the selected predicates are shown, still in arrival order.
  const std::vector<Message> twos = {sent[4], sent[5]};
  BOOST_TEST(taken(m, 1, {2}) == twos, boost::test_tools::per_element());
  m.release(1);
  BOOST_TEST(m.empty(1));
  BOOST_TEST(taken(m, 1).empty());
}

BOOST_AUTO_TEST_CASE(long_chains_and_recycled_chunks_keep_every_message) {
  Mailboxes m(kShapes);
  m.addNodes(3);
  for (int round = 0; round < 3; ++round) {
    std::vector<Message> sent0, sent2;
    // Interleaved posts to two nodes: many chunks each, of one-word and three-word records.
    for (int i = 0; i < 1000; ++i) {
      const Message a{1, i % 7 == 0, {I(i * 37 - 5000 + round)}};
      const Message b{
          2, false, {Value::fromNode(std::uint32_t(i)).bits(), I(-i), Value::fromBool(i % 2).bits()}};
      post(m, 0, a);
      post(m, 2, b);
      sent0.push_back(a);
      sent2.push_back(b);
    }
    BOOST_TEST(taken(m, 0) == sent0, boost::test_tools::per_element());
    BOOST_TEST(taken(m, 2) == sent2, boost::test_tools::per_element());
    std::size_t pending = 0;
    m.forEachPending([&](PredId, const Value*) { ++pending; });
    BOOST_TEST(pending == 2000u);
    const std::size_t reserved = m.bytesReserved();
    m.release(0);
    m.release(2);
    // The next rounds reuse the released chunks: no more memory.
    if (round > 0) BOOST_TEST(m.bytesReserved() == reserved);
  }
}

// Shards of one run (MailSlabs): a node's messages move to another shard's mailboxes as they are.
BOOST_AUTO_TEST_CASE(a_detached_box_joins_another_shards_box_behind_what_waits_there) {
  MailSlabs slabs(2);
  Mailboxes a(kShapes, &slabs, 0), b(kShapes, &slabs, 1);
  a.addNodes(2);
  b.addNodes(2);
  std::vector<Message> sent, already;
  for (int i = 0; i < 300; ++i) {  // many chunks
    sent.push_back({2, i % 5 == 0, {Value::fromNode(std::uint32_t(i)).bits(), I(-i), I(i % 2)}});
    post(a, 1, sent.back());
  }
  already.push_back({1, false, {I(42)}});
  post(b, 1, already.back());
  const Mailboxes::Chain chain = a.detach(1);
  BOOST_TEST(a.empty(1));
  BOOST_TEST(taken(a, 1).empty());
  b.attach(1, chain);
  std::vector<Message> all = already;
  all.insert(all.end(), sent.begin(), sent.end());
  BOOST_TEST(taken(b, 1) == all, boost::test_tools::per_element());
  // Posts queue behind the chain; an empty chain changes nothing.
  const Message later{1, true, {I(-7)}};
  post(b, 1, later);
  b.attach(1, a.detach(0));
  all.push_back(later);
  BOOST_TEST(taken(b, 1) == all, boost::test_tools::per_element());
  // b recycles a's chunks: what b posts next needs no slab of its own.
  const std::size_t reserved = b.bytesReserved();
  b.release(1);
  for (int i = 0; i < 300; ++i) post(b, 0, sent[std::size_t(i)]);
  BOOST_TEST(b.bytesReserved() == reserved);
  BOOST_TEST(taken(b, 0) == sent, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(a_shard_with_plenty_of_free_chunks_leaves_more_to_the_shard_that_runs_out) {
  MailSlabs slabs(2);
  Mailboxes a(kShapes, &slabs, 0), b(kShapes, &slabs, 1);
  a.addNodes(2);
  b.addNodes(1);
  // a fills about 3,000 chunks for node 0, then as many for node 1, and releases both: the first
  // box's chunks stay on its free list, the second's, beyond what it keeps, go to the spares.
  const Message wide{4, false, std::vector<std::uint64_t>(17, I(3))};  // 18 words: one a chunk
  for (int i = 0; i < 3000; ++i) post(a, 0, wide);
  for (int i = 0; i < 3000; ++i) post(a, 1, wide);
  a.release(0);
  a.release(1);
  // b takes those instead of mapping slabs of its own; a's free list serves a.
  const std::size_t reservedA = a.bytesReserved();
  for (int i = 0; i < 3000; ++i) post(b, 0, wide);
  BOOST_TEST(b.bytesReserved() < 64 * 1024u);  // its box array and first small slab at most
  for (int i = 0; i < 3000; ++i) post(a, 0, wide);
  BOOST_TEST(a.bytesReserved() == reservedA);
  BOOST_TEST(taken(b, 0).size() == 3000u);
}

BOOST_AUTO_TEST_CASE(the_first_chunks_come_out_and_go_alone_and_later_posts_queue_behind_the_rest) {
  // A shard's node run takes in only the first chunks of its box (Machine::deliverIncoming).
  // kShapes' widest record (18 words) makes cells of 19 words: one-word records, 18 to the box's
  // first chunk (one cell), 37 to each next (two cells), so 100 messages fill three chunks and
  // start a fourth.
  Mailboxes m(kShapes);
  m.addNodes(1);
  std::vector<Message> sent;
  for (int i = 0; i < 100; ++i) sent.push_back({1, false, {I(i)}});
  for (const Message& msg : sent) post(m, 0, msg);
  const std::vector<Message> first(sent.begin(), sent.begin() + 55);
  BOOST_TEST(taken(m, 0, kAll, 2) == first, boost::test_tools::per_element());
  m.release(0, 2);
  BOOST_TEST(!m.empty(0));
  const Message late{1, true, {I(-7)}};
  post(m, 0, late);
  std::vector<Message> rest(sent.begin() + 55, sent.end());
  rest.push_back(late);
  BOOST_TEST(taken(m, 0) == rest, boost::test_tools::per_element());
  m.release(0, 2);  // the last two chunks: nothing is left
  BOOST_TEST(m.empty(0));
  post(m, 0, late);  // an emptied box starts a new chain
  BOOST_TEST(taken(m, 0) == std::vector<Message>{late}, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(narrow_records_take_less_room) {
  // 300,000 one-int messages take one word each instead of two.
  Mailboxes narrow({{ArgWidth::Int32}});
  Mailboxes wide({{ArgWidth::Word}});
  narrow.addNodes(1);
  wide.addNodes(1);
  // Two values although the predicate has one argument: GCC's -Warray-bounds cannot see that post()
  // reads only the arity's worth, and warns about a one-value buffer.
  const std::vector<Value> v(2, Value::fromInt(42));
  for (int i = 0; i < 300000; ++i) {
    narrow.post(0, 0, false, v.data());
    wide.post(0, 0, false, v.data());
  }
  BOOST_TEST(narrow.bytesReserved() < wide.bytesReserved());
  std::size_t seen = 0;
  narrow.forEach(
      0, [](PredId) { return true; },
      [&](PredId, bool, const Value* args) { seen += args[0].asInt() == 42; });
  BOOST_TEST(seen == 300000u);
}

BOOST_AUTO_TEST_CASE(mixed_records_take_less_room) {
  // (node, float): the node in the first word's free half, two words instead of three.
  Mailboxes mixed({{ArgWidth::Uint32, ArgWidth::Word}});
  Mailboxes whole({{ArgWidth::Word, ArgWidth::Word}});
  mixed.addNodes(1);
  whole.addNodes(1);
  const std::vector<Value> v = {Value::fromNode(3), Value::fromFloat(0.5)};
  for (int i = 0; i < 300000; ++i) {
    mixed.post(0, 0, false, v.data());
    whole.post(0, 0, false, v.data());
  }
  BOOST_TEST(mixed.bytesReserved() < whole.bytesReserved() * 3 / 4);
  std::size_t seen = 0;
  mixed.forEach(
      0, [](PredId) { return true; },
      [&](PredId, bool, const Value* args) { seen += args[0].bits() == 3 && args[1].asFloat() == 0.5; });
  BOOST_TEST(seen == 300000u);
}

BOOST_AUTO_TEST_CASE(a_box_with_few_messages_takes_one_small_chunk) {
  // 2,000 nodes with a message or two each: 2,000 cells of 128 bytes, all in the first two slabs
  // (2,080 cells), where chunks of 256 bytes took a third slab.
  Mailboxes m({{ArgWidth::Int32}});
  m.addNodes(2000);
  const std::vector<Value> v(2, Value::fromInt(-9));
  for (NodeId n = 0; n < 2000; ++n)
    for (NodeId k = 0; k <= n % 2; ++k) m.post(n, 0, false, v.data());
  BOOST_TEST(m.bytesReserved() < 2000u * 256);
  std::size_t seen = 0;
  for (NodeId n = 0; n < 2000; ++n)
    m.forEach(
        n, [](PredId) { return true; },
        [&](PredId, bool, const Value* args) { seen += args[0].asInt() == -9; });
  BOOST_TEST(seen == 3000u);
}

BOOST_AUTO_TEST_CASE(spare_chunks_of_one_size_wait_for_a_shard_that_needs_that_size) {
  MailSlabs slabs(2);
  const std::vector<std::vector<ArgWidth>> shapes = {{ArgWidth::Int32}};
  Mailboxes a(shapes, &slabs, 0), b(shapes, &slabs, 1);
  a.addNodes(8000);
  b.addNodes(1);
  const std::vector<Value> v(2, Value::fromInt(1));
  auto oneEach = [&] {  // 8,000 small chunks
    for (NodeId n = 0; n < 8000; ++n) a.post(n, 0, false, v.data());
  };
  oneEach();
  for (NodeId n = 0; n < 8000; ++n) a.release(n);  // beyond what a keeps, to the spares
  const std::size_t reservedA = a.bytesReserved();
  // b needs big chunks only: it maps its own and leaves the small spares alone.
  for (int i = 0; i < 20000; ++i) b.post(0, 0, false, v.data());
  oneEach();
  BOOST_TEST(a.bytesReserved() == reservedA);
  BOOST_TEST(taken(b, 0).size() == 20000u);
}

BOOST_AUTO_TEST_CASE(argument_widths_follow_the_field_types) {
  BOOST_TEST((argWidth(TypeKind::Int) == ArgWidth::Int32));
  BOOST_TEST((argWidth(TypeKind::Node) == ArgWidth::Uint32));
  BOOST_TEST((argWidth(TypeKind::Bool) == ArgWidth::Uint32));
  BOOST_TEST((argWidth(TypeKind::Thread) == ArgWidth::Uint32));
  BOOST_TEST((argWidth(TypeKind::Float) == ArgWidth::Word));   // a double needs 8 bytes
  BOOST_TEST((argWidth(TypeKind::String) == ArgWidth::Word));  // a pointer
  BOOST_TEST((argWidth(TypeKind::List) == ArgWidth::Word));
}

// Random posts, partial and whole releases, and boxes moving between two shards, against a
// model of one queue per node: every message comes back once, in order, with its arguments,
// whatever sizes of chunk its box went through and whichever shard's free lists they came from.
BOOST_AUTO_TEST_CASE(random_traffic_between_two_shards_agrees_with_a_queue_per_node) {
  MailSlabs slabs(2);
  Mailboxes shard[2] = {Mailboxes(kShapes, &slabs, 0), Mailboxes(kShapes, &slabs, 1)};
  constexpr NodeId kNodes = 64;
  for (Mailboxes& m : shard) m.addNodes(kNodes);
  std::vector<std::deque<Message>> model(kNodes);
  std::vector<int> owner(kNodes);
  for (NodeId n = 0; n < kNodes; ++n) owner[n] = int(n % 2);
  std::mt19937 rng(11);
  auto randomMessage = [&] {
    const PredId p = PredId(rng() % kAll.size());
    Message msg{p, rng() % 2 == 0, {}};
    for (ArgWidth w : kShapes[p]) {
      const std::uint32_t r = std::uint32_t(rng());
      msg.bits.push_back(w == ArgWidth::Word    ? (std::uint64_t(rng()) << 32 | r)
                         : w == ArgWidth::Int32 ? Value::fromInt(std::int32_t(r)).bits()
                                                : Value::fromNode(r).bits());
    }
    return msg;
  };
  for (int step = 0; step < 200000; ++step) {
    const NodeId n = NodeId(rng() % kNodes);
    Mailboxes& m = shard[owner[n]];
    const unsigned what = rng() % 100;
    if (what < 80) {  // bursts of one to a few dozen messages, rarely of thousands (spare chunks)
      const unsigned burst = rng() % 4000 == 0 ? 20000 : 1 + (rng() % 4 == 0 ? rng() % 40 : 0);
      for (unsigned k = burst; k > 0; --k) {
        model[n].push_back(randomMessage());
        post(m, n, model[n].back());
      }
    } else if (what < 95) {  // taken in: the whole box or its first chunks
      const std::uint32_t chunks = rng() % 2 ? Mailboxes::kAllChunks : 1 + rng() % 3;
      const std::vector<Message> got = taken(m, n, kAll, chunks);
      BOOST_REQUIRE_LE(got.size(), model[n].size());
      for (std::size_t i = 0; i < got.size(); ++i) BOOST_REQUIRE(got[i] == model[n][i]);
      if (chunks == Mailboxes::kAllChunks) BOOST_REQUIRE_EQUAL(got.size(), model[n].size());
      m.release(n, chunks);
      model[n].erase(model[n].begin(), model[n].begin() + std::ptrdiff_t(got.size()));
      BOOST_REQUIRE_EQUAL(m.empty(n), model[n].empty());
    } else {  // the node moves to the other shard, its messages along
      const int to = 1 - owner[n];
      shard[to].attach(n, m.detach(n));
      owner[n] = to;
    }
  }
  for (NodeId n = 0; n < kNodes; ++n) {
    const std::vector<Message> rest(model[n].begin(), model[n].end());
    BOOST_REQUIRE(taken(shard[owner[n]], n) == rest);
  }
}
