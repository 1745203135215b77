// Values handed from one thread's heap to another's (meldvm/heap.hpp: Heap::share): counted
// atomically once shared, freed by whichever thread drops the last reference, their blocks back
// in the heap that allocated them. ThreadSanitizer runs this file (label threads).
#define BOOST_TEST_MODULE threads_heap_handover
#include <boost/test/unit_test.hpp>
#include <string>
#include <thread>
#include <vector>

#include "meldvm/heap.hpp"

using meldvm::Heap;
using meldvm::TypeId;
using meldvm::TypeTable;
using meldvm::Value;

namespace {

Value intList(Heap& heap, TypeId listType, int from, int count, Value tail = Value::nil()) {
  std::vector<Value> items;
  for (int i = 0; i < count; ++i) items.push_back(Value::fromInt(from + i));
  return heap.makeList(listType, items, tail);
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_shared_list_freed_by_another_heap_goes_back_to_its_own) {
  TypeTable types;
  const TypeId li = types.list(TypeTable::kInt);
  Heap a(types), b(types);
  const Value list = intList(a, li, 0, 100);
  BOOST_TEST(a.liveObjects() == 100u);
  a.share(li, list);
  b.retain(li, list);   // b's reference
  a.release(li, list);  // a lets go: the cells live on for b
  BOOST_TEST(a.liveObjects() == 100u);
  // b conses onto the shared tail: its new cell is b's own, private, and points into a's heap.
  const Value longer = b.cons(li, Value::fromInt(-1), list);
  b.release(li, list);
  BOOST_TEST(b.liveObjects() == 1u);
  b.release(li, longer);  // frees b's cell, then a's 100 through a's remote-free stack
  BOOST_TEST(b.liveObjects() == 0u);
  BOOST_TEST(a.liveObjects() == 0u);
  // The blocks are a's again: a new list reuses them instead of growing the heap.
  const std::size_t reserved = a.bytesReserved();
  const Value again = intList(a, li, 0, 100);
  BOOST_TEST(a.bytesReserved() == reserved);
  a.release(li, again);
}

// A big heap's later slabs are cut from chunks of huge pages (Heap::newSlab): a block there finds
// its owner from its address as well, and comes back to it from another thread.
BOOST_AUTO_TEST_CASE(blocks_cut_from_huge_chunks_go_back_to_their_own_heap) {
  TypeTable types;
  const TypeId li = types.list(TypeTable::kInt);
  Heap a(types), b(types);
  const int cells = 300000;  // 7 MB of cells: past the slabs a heap takes one by one (2 MiB)
  const Value list = intList(a, li, 0, cells);
  const std::size_t reserved = a.bytesReserved();
  BOOST_TEST(reserved > std::size_t(4) << 20);
  a.share(li, list);
  b.retain(li, list);
  a.release(li, list);
  b.release(li, list);  // b frees them all, each through a's remote-free stack
  BOOST_TEST(b.liveObjects() == 0u);
  BOOST_TEST(a.liveObjects() == 0u);
  BOOST_TEST(a.bytesInUse() == 0u);
  const Value again = intList(a, li, 0, cells);  // the same blocks again: no new chunk
  BOOST_TEST(a.bytesReserved() == reserved);
  a.release(li, again);
  BOOST_TEST(a.liveObjects() == 0u);
}

BOOST_AUTO_TEST_CASE(sharing_marks_what_a_value_reaches_and_stops_at_what_is_shared) {
  TypeTable types;
  const TypeId ls = types.list(TypeTable::kString);
  const TypeId fields[] = {ls, TypeTable::kString};
  const TypeId st = types.structOf(fields);
  Heap a(types), b(types);
  const Value big = a.makeString(std::string(2000, 'x'));  // a large block (own header)
  const Value small = a.makeString("y");
  const Value items[] = {small, big};
  const Value strings = a.makeList(ls, items);
  const Value pair[] = {strings, big};
  const Value s = a.makeTuple(st, pair);
  a.release(TypeTable::kString, big);
  a.release(TypeTable::kString, small);
  a.release(ls, strings);
  a.share(st, s);
  a.share(st, s);  // already shared: nothing more to do
  b.retain(st, s);
  a.release(st, s);
  BOOST_TEST(a.liveObjects() == 5u);  // the struct, 2 cells, 2 strings
  b.release(st, s);
  // b put off the list's second cell (Heap::destroy): a's blocks come back once b drops its
  // deferred tails, which counting b's own objects does first.
  BOOST_TEST(b.liveObjects() == 0u);
  BOOST_TEST(a.liveObjects() == 0u);
  BOOST_TEST(a.bytesInUse() == 0u);
}

// Two threads take and drop references to the same shared lists at once, and each frees some of
// them last: the counts stay exact (every block comes back once, no object is freed twice). a
// holds one reference to each list when called; b takes one.
namespace {
void churnFromTwoThreads(Heap& a, Heap& b, TypeId li, const std::vector<Value>& lists) {
  constexpr int kRounds = 200;
  for (Value l : lists) b.retain(li, l);  // one reference each for a and b
  auto churn = [&](Heap& heap, std::size_t parity) {
    for (int r = 0; r < kRounds; ++r)
      for (Value l : lists) {
        heap.retain(li, l);
        heap.release(li, l);
      }
    for (std::size_t i = 0; i < lists.size(); ++i)
      if (i % 2 == parity) heap.release(li, lists[i]);
  };
  std::thread other([&] { churn(b, 1); });
  churn(a, 0);
  other.join();
  // Half the lists still have a's reference, half b's.
  for (std::size_t i = 0; i < lists.size(); ++i) (i % 2 == 0 ? b : a).release(li, lists[i]);
  BOOST_TEST(b.liveObjects() == 0u);
  BOOST_TEST(a.liveObjects() == 0u);
}
}  // namespace

BOOST_AUTO_TEST_CASE(two_threads_count_shared_lists_exactly) {
  TypeTable types;
  const TypeId li = types.list(TypeTable::kInt);
  Heap a(types), b(types);
  std::vector<Value> lists;
  const Value tail = intList(a, li, 0, 50);
  for (int i = 0; i < 200; ++i) lists.push_back(a.cons(li, Value::fromInt(i), tail));
  a.release(li, tail);
  for (Value l : lists) a.share(li, l);
  churnFromTwoThreads(a, b, li, lists);
}

// Heap::shareAll (a moving node's facts, fetched ahead): every object the listed ones reach is
// shared, past the prefetch distances, whether its tail is private, shared by a sibling listed
// before it, or shared already; a list listed twice is walked once.
BOOST_AUTO_TEST_CASE(share_all_shares_what_every_listed_object_reaches) {
  TypeTable types;
  const TypeId li = types.list(TypeTable::kInt);
  Heap a(types), b(types);
  const Value privateTail = intList(a, li, 0, 30);
  const Value sharedTail = intList(a, li, 100, 5);
  a.share(li, sharedTail);
  std::vector<Value> lists;
  for (int i = 0; i < 100; ++i) {
    const Value second = a.cons(li, Value::fromInt(1000 + i), i % 3 == 0 ? sharedTail : privateTail);
    lists.push_back(a.cons(li, Value::fromInt(i), second));
    a.release(li, second);
  }
  a.release(li, privateTail);
  a.release(li, sharedTail);
  std::vector<meldvm::Object*> objects;
  for (Value l : lists) objects.push_back(l.asObject());
  objects.push_back(lists.front().asObject());
  a.shareAll(objects);
  churnFromTwoThreads(a, b, li, lists);
}
