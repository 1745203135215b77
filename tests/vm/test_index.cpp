// Indexes on one field and the hash table under them: matching facts come out in insertion order,
// per node, through insertions, consumptions and in-place updates; a long random run is checked
// against a plain scan of the node's list.
#define BOOST_TEST_MODULE vm_index
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <random>
#include <unordered_map>

#include "meldvm/slot_hash.hpp"
#include "vm_fixture.hpp"

using namespace vmtest;

namespace {

std::vector<int> byKey(Database& db, NodeId n, PredId p, std::uint32_t index, Value key) {
  std::vector<int> out;
  for (FactRef f = db.firstWithKey(n, p, index, key); f != kNoFact; f = db.nextWithKey(p, index, f))
    out.push_back(db.args(p, f)[1].asInt());
  return out;
}

std::vector<int> byScan(Database& db, NodeId n, PredId p, std::uint32_t field, Value key) {
  std::vector<int> out;
  for (FactRef f = db.first(n, p); f != kNoFact; f = db.next(p, f))
    if (db.args(p, f)[field].bits() == key.bits()) out.push_back(db.args(p, f)[1].asInt());
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(index_lists_matching_facts_in_insertion_order) {
  Store s;
  const PredId e = s.linear("edge", {TypeTable::kNode, TypeTable::kInt});
  Database& db = s.open(2);
  const std::uint32_t ix = db.requestIndex(e, 0);
  BOOST_TEST(db.requestIndex(e, 0) == ix);  // idempotent
  std::vector<FactRef> refs;
  const NodeId dest[] = {1, 2, 1, 1, 3, 2};
  for (int i = 0; i < 6; ++i) refs.push_back(db.addLinear(0, e, std::vector<Value>{N(dest[i]), I(i)}.data()));
  db.addLinear(1, e, std::vector<Value>{N(1), I(99)}.data());
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({0, 2, 3}), boost::test_tools::per_element());
  BOOST_TEST(byKey(db, 0, e, ix, N(2)) == std::vector<int>({1, 5}), boost::test_tools::per_element());
  BOOST_TEST(byKey(db, 0, e, ix, N(7)).empty());
  BOOST_TEST(byKey(db, 1, e, ix, N(1)) == std::vector<int>({99}), boost::test_tools::per_element());

  db.consume(0, e, refs[0]);  // chain head
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({2, 3}), boost::test_tools::per_element());
  db.consume(0, e, refs[3]);  // chain tail
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({2}), boost::test_tools::per_element());
  db.addLinear(0, e, std::vector<Value>{N(1), I(6)}.data());  // appended after the new tail
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({2, 6}), boost::test_tools::per_element());
  db.consume(0, e, refs[4]);  // a one-fact chain disappears
  BOOST_TEST(byKey(db, 0, e, ix, N(3)).empty());
  // An update that changes the key moves the fact to the other chain, at its place in the list
  // (list: 1, 2, 5, 6), which the established VM scans.
  db.updateLinear(0, e, refs[1], std::vector<Value>{N(1), I(1)}.data(), false);
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({1, 2, 6}), boost::test_tools::per_element());
  BOOST_TEST(byKey(db, 0, e, ix, N(2)) == std::vector<int>({5}), boost::test_tools::per_element());
  // Same key, fact kept in place: the chain does not change; moved to the end of the list: the
  // chain's end too.
  db.updateLinear(0, e, refs[1], std::vector<Value>{N(1), I(7)}.data(), false);
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({7, 2, 6}), boost::test_tools::per_element());
  db.updateLinear(0, e, refs[1], std::vector<Value>{N(1), I(8)}.data(), true);
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({2, 6, 8}), boost::test_tools::per_element());
  // A key that changes in the middle of the list: the fact joins the chain between two others.
  db.updateLinear(0, e, refs[5], std::vector<Value>{N(1), I(5)}.data(), false);  // list: 2, 5, 6, 8
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({2, 5, 6, 8}), boost::test_tools::per_element());
  BOOST_TEST(byKey(db, 0, e, ix, N(2)).empty());
  // ... and ahead of all of them: it becomes the chain's head.
  db.updateLinear(0, e, refs[2], std::vector<Value>{N(4), I(2)}.data(), false);
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({5, 6, 8}), boost::test_tools::per_element());
  db.updateLinear(0, e, refs[2], std::vector<Value>{N(1), I(2)}.data(), false);
  BOOST_TEST(byKey(db, 0, e, ix, N(1)) == std::vector<int>({2, 5, 6, 8}), boost::test_tools::per_element());
  BOOST_TEST(byKey(db, 0, e, ix, N(4)).empty());
}

BOOST_AUTO_TEST_CASE(index_on_persistent_and_string_keys) {
  Store s;
  const PredId p = s.persistent("name", {TypeTable::kString, TypeTable::kInt});
  Database& db = s.open(1);
  const std::uint32_t ix = db.requestIndex(p, 0);
  Value x = s.heap.makeString("x"), y = s.heap.makeString("y"), x2 = s.heap.makeString("x");
  db.derive(0, p, std::vector<Value>{x, I(1)}.data());
  db.derive(0, p, std::vector<Value>{y, I(2)}.data());
  db.derive(0, p, std::vector<Value>{x2, I(3)}.data());
  db.derive(0, p, std::vector<Value>{x2, I(1)}.data());  // a copy: same slot, count 2
  std::vector<int> got;
  for (FactRef f = db.firstWithKey(0, p, ix, x2); f != kNoFact; f = db.nextWithKey(p, ix, f))
    got.push_back(db.args(p, f)[1].asInt() * 10 + int(db.copies(p, f)));
  BOOST_TEST(got == std::vector<int>({12, 31}), boost::test_tools::per_element());
  for (Value v : {x, y, x2}) s.heap.release(TypeTable::kString, v);
}

namespace {

// 20000 random insertions, consumptions and in-place updates of e(key, step) facts over `nodes`
// nodes, with between minLive and maxLive facts alive; every `every` steps, each node's facts of
// each key come out of the index as a scan of its list finds them (the chains keep the list's
// order, updates included). Counts the checks of nodes with at most 8 facts, and the others.
struct Churn {
  NodeId nodes;
  int keys;
  std::uint32_t seed;
  std::size_t minLive = 1, maxLive = ~std::size_t(0);
  int every = 97;
  std::uint32_t small = 0, large = 0;

  void run() {
    Store s;
    const PredId e = s.linear("e", {TypeTable::kInt, TypeTable::kInt});
    Database& db = s.open(nodes);
    const std::uint32_t ix = db.requestIndex(e, 0);
    std::mt19937 rng(seed);
    std::vector<std::pair<NodeId, FactRef>> live;
    for (int step = 0; step < 20000; ++step) {
      const int op = int(rng() % 10);
      if (op < 5 || live.size() < minLive) {
        const NodeId n = rng() % nodes;
        live.push_back({n, db.addLinear(n, e, std::vector<Value>{I(int(rng() % keys)), I(step)}.data())});
      } else if (op < 9 || live.size() > maxLive) {
        const std::size_t k = rng() % live.size();
        db.consume(live[k].first, e, live[k].second);
        live[k] = live.back();
        live.pop_back();
      } else {
        const std::size_t k = rng() % live.size();
        db.updateLinear(live[k].first, e, live[k].second,
                        std::vector<Value>{I(int(rng() % keys)), I(step)}.data(), rng() % 2);
      }
      if (step % every == 0)
        for (NodeId n = 0; n < nodes; ++n) {
          (db.factCount(n, e) <= 8 ? small : large) += 1;
          for (int key = 0; key < keys; ++key)
            BOOST_REQUIRE(byKey(db, n, e, ix, I(key)) == byScan(db, n, e, 0, I(key)));
        }
    }
    std::size_t total = 0;
    for (NodeId n = 0; n < nodes; ++n) total += db.factCount(n, e);
    BOOST_TEST(total == live.size());
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(random_churn_matches_a_scan) {
  Churn c{3, 7, 12345};  // thousands of facts per node: the hash table
  c.run();
  BOOST_TEST(c.large > 0u);
}

BOOST_AUTO_TEST_CASE(small_lists_found_by_walking_them_agree_with_the_hash_table) {
  // A node with at most 8 facts of the predicate finds a key by walking its list, a larger one
  // through the hash table: lists that grow and shrink across that size give the scan's answer
  // either way.
  Churn c{40, 4, 99, 200, 400, 89};
  c.run();
  BOOST_TEST(c.small > 1000u);  // both ways were taken many times
  BOOST_TEST(c.large > 1000u);
}

BOOST_AUTO_TEST_CASE(a_walked_list_yields_the_head_of_the_index_chain) {
  // Persistent facts are listed grouped by their first field, while an index on another field
  // chains them in insertion order: the walk must start the chain at its head, not at the first
  // fact of the list with the key. Node 1 holds the same facts and ten more (the hash table).
  Store s;
  const PredId p = s.persistent("p", {TypeTable::kInt, TypeTable::kInt, TypeTable::kInt});
  Database& db = s.open(2);
  const std::uint32_t ix = db.requestIndex(p, 1);
  for (NodeId n : {NodeId(0), NodeId(1)}) {
    db.derive(n, p, std::vector<Value>{I(2), I(6), I(0)}.data());
    db.derive(n, p, std::vector<Value>{I(1), I(5), I(1)}.data());  // the chain's head
    db.derive(n, p, std::vector<Value>{I(2), I(5), I(2)}.data());  // listed before it, in group 2
  }
  for (int i = 0; i < 10; ++i) db.derive(1, p, std::vector<Value>{I(9), I(6), I(i)}.data());
  auto third = [&](NodeId n) {
    std::vector<int> out;
    for (FactRef f = db.firstWithKey(n, p, ix, I(5)); f != kNoFact; f = db.nextWithKey(p, ix, f))
      out.push_back(db.args(p, f)[2].asInt());
    return out;
  };
  BOOST_TEST(db.factCount(0, p) == 3u);
  BOOST_TEST(db.factCount(1, p) == 13u);
  BOOST_TEST(third(1) == std::vector<int>({1, 2}), boost::test_tools::per_element());
  BOOST_TEST(third(0) == third(1), boost::test_tools::per_element());
  BOOST_TEST(db.firstWithKey(0, p, ix, I(7)) == kNoFact);
}

BOOST_AUTO_TEST_CASE(slot_hash_agrees_with_a_map) {
  // Keys collide on purpose (hash = key % 64) to exercise probing and backward-shift deletion.
  SlotHash h;
  std::unordered_map<std::uint32_t, bool> ref;
  std::mt19937 rng(7);
  const auto hashOf = [](std::uint32_t k) { return std::uint64_t(k % 64) * 0x9e3779b97f4a7c15ull; };
  for (int step = 0; step < 50000; ++step) {
    const std::uint32_t k = rng() % 500;
    const auto eq = [&](std::uint32_t slot) { return slot == k; };
    const bool present = ref.count(k) != 0;
    BOOST_REQUIRE_EQUAL(h.find(hashOf(k), eq) == k, present);
    if (present) {
      BOOST_REQUIRE(h.erase(hashOf(k), k));
      ref.erase(k);
    } else {
      h.insert(hashOf(k), k);
      ref[k] = true;
    }
    BOOST_REQUIRE_EQUAL(h.size(), ref.size());
  }
  for (std::uint32_t k = 0; k < 500; ++k)
    BOOST_REQUIRE_EQUAL(h.find(hashOf(k), [&](std::uint32_t slot) { return slot == k; }) == k,
                        ref.count(k) != 0);
  BOOST_TEST(!h.erase(hashOf(1000), 1000));
  const std::size_t cap = h.capacity();
  for (int i = 0; i < 1000; ++i) {  // churn at a steady size: the table does not grow
    const std::uint32_t k = 600 + std::uint32_t(i % 10);
    h.insert(hashOf(k), k);
    h.erase(hashOf(k), k);
  }
  BOOST_TEST(h.capacity() == cap);
}

BOOST_AUTO_TEST_CASE(slot_hash_shrinks_to_a_quarter_full_and_keeps_every_key) {
  SlotHash h;
  const auto hashOf = [](std::uint32_t k) { return std::uint64_t(k) * 0x9e3779b97f4a7c15ull; };
  for (std::uint32_t k = 0; k < 10000; ++k) h.insert(hashOf(k), k);
  BOOST_TEST(h.shrink() == 0u);  // over a quarter full already
  const std::size_t full = h.capacity();
  for (std::uint32_t k = 0; k < 10000; ++k)
    if (k % 10 != 0) BOOST_REQUIRE(h.erase(hashOf(k), k));
  BOOST_TEST(h.shrink() == (full - 4096) * 8);  // 1,000 keys: 4,096 entries
  BOOST_TEST(h.capacity() == 4096u);
  for (std::uint32_t k = 0; k < 10000; ++k)
    BOOST_REQUIRE_EQUAL(h.find(hashOf(k), [&](std::uint32_t slot) { return slot == k; }) == k, k % 10 == 0);
  for (std::uint32_t k = 0; k < 1000; ++k)
    if (k % 10 != 0) h.insert(hashOf(k), k);  // 1,900 keys: it grows again at half full
  BOOST_TEST(h.capacity() == 4096u);
  BOOST_TEST(h.size() == 1900u);
}
