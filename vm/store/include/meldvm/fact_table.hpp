// The storage of one relation for all nodes: a predicate's visible facts, or the inputs of an
// aggregated predicate. Facts live in one growing array of fixed-size slots (recycled through a
// free list, so the steady state allocates nothing), and each node's facts form a doubly-linked
// list through their slots, in insertion order. The list heads are kept by the caller (the
// Database keeps them node-major, so one node's heads share cache lines).
//
// Slot layout, in 8-byte words: [prev | next] [node | count] then one [prev | next] word per index
// chain, then the arguments (home excluded). A free slot has count 0 and links through `next`.
//
// Optional de-duplication table (persistent facts: node + all arguments -> slot) and optional
// indexes: an index on a key (a run of fields) keeps, per (node, key value), a chain of the facts
// with that key in insertion order; the hash table maps the key to the chain head, whose `prev`
// link points at the chain tail.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/key_hash.hpp"
#include "meldvm/large_allocator.hpp"
#include "meldvm/reference_fields.hpp"
#include "meldvm/slot_hash.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

using FactRef = std::uint32_t;
inline constexpr FactRef kNoFact = 0xFFFFFFFFu;

struct ListHead {
  FactRef first = kNoFact;
  FactRef last = kNoFact;
  std::uint32_t size = 0;  // number of slots (distinct facts) in the list
};

class alignas(64) FactTable {  // 256 bytes, whole cache lines: see fact_table.cpp
 public:
  struct KeySpec {
    std::uint32_t first, count;  // key = fields [first, first + count); count may be 0 (node only)
  };

  FactTable(const TypeTable& types, Heap& heap, std::vector<TypeId> fields, bool dedup);
  ~FactTable();  // releases the boxed arguments of the facts still stored
  FactTable(FactTable&&) = default;

  // Room for `facts` facts without growing (a caller that knows the count saves the doubling).
  void reserve(std::size_t facts);
  // Indexes must be added while the table is empty (the slot layout depends on their number).
  std::uint32_t addIndex(KeySpec key);
  std::uint32_t indexCount() const { return std::uint32_t(indexes_.size()); }
  KeySpec indexKey(std::uint32_t index) const { return indexes_[index].key; }

  // Adds a fact to the node's list (at the end, or right after `after`) and at the end of its index
  // chains; the boxed arguments are retained.
  // adopt: the caller hands its references to the boxed arguments over (no retain).
  FactRef insert(ListHead& list, NodeId node, const Value* args, std::uint32_t count, FactRef after = kNoFact,
                 bool adopt = false);
  // insert(list, node, args + i * arity(), 1) for each i < facts; on a table with no index and no
  // de-duplication (a compact predicate's: a data file's facts) the slot array grows once.
  void appendEach(ListHead& list, NodeId node, const Value* args, std::uint32_t facts);
  // insert(list, node, args, 1, kNoFact, /*adopt=*/true), inline where it is simplest: a table
  // with no index and no de-duplication (a linear predicate's) that has a free slot to reuse,
  // which is every insertion of the steady state.
  FactRef insertAdopted(ListHead& list, NodeId node, const Value* args) {
    if (!plain_ || freeList_ == kNoFact) [[unlikely]]
      return insert(list, node, args, 1, kNoFact, true);
    const FactRef f = freeList_;
    freeList_ = next(f);
    fill(list, f, node, args, 1, list.last, kNoFact);
    return f;
  }
  // Adds a fact right after the last fact of the node with the same index-0 key (at the end of
  // the list when there is none): persistent facts grouped by their first field. One hash look-up
  // finds the group and links the index.
  FactRef insertGrouped(ListHead& list, NodeId node, const Value* args, std::uint32_t count);
  // Removes a fact; its boxed arguments are released. Read next(f) before erasing f. (Inline:
  // the rule engine consumes a fact for nearly every fact it derives.)
  void erase(ListHead& list, FactRef f) {
    if (!plain_) unhash(f);
    Value* w = words_.data() + base(f);
    const FactRef p = std::uint32_t(w[0].bits()), nx = std::uint32_t(w[0].bits() >> 32);
    connect(list, p, nx);
    --list.size;
    if (referencePattern_ >= 0)
      heap_.releaseObject(w[argOffset_ + std::uint32_t(referencePattern_)]);
    else if (referencePattern_ == ReferenceFields::kSeveralReferences)
      references_.release(heap_, w + argOffset_);
    w[1] = Value::fromBits(0);  // count 0 marks the slot free
    w[0] = Value::fromBits((std::uint64_t(freeList_) << 32) | p);
    freeList_ = f;
    --live_;
  }
  void moveToBack(ListHead& list, FactRef f) {
    if (list.last == f) return;
    connect(list, prevOf(f), next(f));  // f is not the last: list.last stays
    const FactRef last = list.last;
    connect(list, last, f);
    connect(list, f, kNoFact);
  }
  // New arguments for a stored fact (in-place update), after any move in the list: its index
  // chains keep the list's order. (Inline for a table of plain words with no index.)
  void replaceArgs(const ListHead& list, FactRef f, const Value* args) {
    if ((!plain_ || !references_.empty()) && !(keyedWords_ && keysKept(list, f, args))) [[unlikely]]
      return replaceIndexedArgs(list, f, args);
    copyArgs(words_.data() + base(f) + argOffset_, args, arity());
  }
  // A keyedWords_ table's fact keeps its place in every index chain with these arguments: each
  // key keeps its value and, when the fact is last in its list (it just moved there), no fact
  // with its key follows it (new-heat-transfer's updates: 155 instructions each through
  // replaceIndexedArgs, which works it out for any table). replaceIndexedArgs' own test per chain,
  // by bits: a float key whose bits differ goes there even if equal (+0.0, -0.0). Sharing its
  // typed test cost 1 % of new-heat-transfer's bytecode instructions.
  bool keysKept(const ListHead& list, FactRef f, const Value* args) const {
    const Value* old = words_.data() + base(f) + argOffset_;
    const bool last = list.last == f;
    for (std::uint32_t x = 0, n = indexCount(); x < n; ++x) {
      const std::uint32_t k = indexes_[x].key.first;
      if (old[k].bits() != args[k].bits() || (last && hi(linkWord(f, x)) != kNoFact)) return false;
    }
    return true;
  }
  void setCount(FactRef f, std::uint32_t count) { setHi(base(f) + 1, count); }

  // De-duplicating tables only: the fact of this node with exactly these arguments, or kNoFact.
  FactRef find(NodeId node, const Value* args) const;
  // (Out of line: inline in the interpreter's loop, it saved pagerank-movies 0.7 % of its
  // instructions and cost belief-propagation-50 0.4 % and new-heat-transfer-80 0.3 %.)
  FactRef firstWithKey(NodeId node, std::uint32_t index, const Value* key) const;
  // The same, found by walking the node's list from `first` instead of the hash table.
  FactRef firstInListWithKey(FactRef first, std::uint32_t index, const Value* key) const {
    for (FactRef f = first; f != kNoFact; f = next(f))
      // The chain's head: the fact before it in the chain is the tail (the head links to it).
      if (keyEqualIn(index, f, key) && hi(linkWord(lo(linkWord(f, index)), index)) == kNoFact) return f;
    return kNoFact;
  }
  // Hints that find / firstWithKey with these arguments come soon.
  [[gnu::always_inline]] void prefetchFind(NodeId node, const Value* args) const {
    facts_.prefetch(hashKey(node, args, KeySpec{0, arity()}));  // not memoised: a later key
  }
  [[gnu::always_inline]] void prefetchKey(NodeId node, std::uint32_t index, const Value* key) const {
    indexes_[index].heads.prefetch(hashKey(node, key, indexes_[index].key));
  }
  FactRef nextWithKey(std::uint32_t index, FactRef f) const { return hi(linkWord(f, index)); }
  FactRef lastWithKey(NodeId node, std::uint32_t index, const Value* key) const {
    const FactRef head = firstWithKey(node, index, key);
    return head == kNoFact ? kNoFact : lo(linkWord(head, index));  // the head's prev is the tail
  }

  FactRef next(FactRef f) const { return hi(base(f)); }
  const Value* slotAddress(FactRef f) const { return words_.data() + base(f); }  // for prefetching
  NodeId node(FactRef f) const { return lo(base(f) + 1); }
  std::uint32_t count(FactRef f) const { return hi(base(f) + 1); }
  // Valid until the next insertion into this table (the slot array may move).
  const Value* args(FactRef f) const { return words_.data() + base(f) + argOffset_; }

  // Native code steps through the facts itself (native_abi.h's meld_native_loop): where the slot
  // array is (the array moves when the table grows; this address does not) and words per slot.
  const Value* const* slotArrayAddress() const { return &slotArray_; }
  std::uint32_t stride() const { return stride_; }
  // No index, no de-duplication, no argument holding a reference: a fact is words anyone may write.
  bool plainWords() const { return plain_ && references_.empty(); }
  std::uint32_t argOffset() const { return argOffset_; }
  // Native code unlinks the consumed facts of a table of plain words itself (native_abi.h): it
  // writes the free list's head and the count of live facts.
  FactRef* freeListAddress() { return &freeList_; }
  std::uint32_t* liveAddress() { return &live_; }
  // Native code looks keys up in an index and updates an indexed fact in place itself
  // (native_abi.h's meld_native_field_index): the index's hash table, whether its key hashes as
  // integerHash, and whether the facts are words native code may write while every index's key
  // stays as it is (no de-duplication, no argument holding a reference).
  const SlotHash& indexHeads(std::uint32_t index) const { return indexes_[index].heads; }
  bool integerIndex(std::uint32_t index) const { return indexes_[index].integer; }
  bool wordsUnderIndexes() const { return !dedup_ && references_.empty(); }
  // The slot word of index `index`'s chain (after the list links and the count): its high half
  // links a fact to the next one, its low half to the previous (the head's: to the tail).
  static constexpr std::uint32_t indexLinkWord(std::uint32_t index) { return 2 + index; }

  std::uint32_t arity() const { return std::uint32_t(fields_.size()); }
  const std::vector<TypeId>& fields() const { return fields_; }
  std::uint32_t liveFacts() const { return live_; }
  // Gives back the memory pages whose slots are all free, when a quarter of the slots and at least
  // 256 KiB are free: a shard that gave most of its nodes to another keeps their slots otherwise
  // (heat-transfer at -j 2: one shard gave 4,300 of its 5,000 nodes and kept 3 MB of free slots
  // while the other filled as much). Those slots leave the free list; they are taken again,
  // zeroed, when it is empty, before the array grows. Its hash tables shrink while they stay at
  // most a quarter full. Returns the bytes given back.
  std::size_t releaseFreePages();
  // Memory held: the slot array and the hash tables (de-duplication and indexes).
  std::size_t bytesReserved() const {
    std::size_t b = words_.capacity() * sizeof(Value) + facts_.capacity() * 8;
    for (const Index& x : indexes_) b += x.heads.capacity() * 8;
    return b;
  }

  // Hash of a node and `count` key values with the types of fields [first, first + count).
  // Keys of ints, bools, nodes and threads only (pagerank's neighbour, every ITER_KEY on a node)
  // hash and compare their bits, in leaf functions; the others go through the types' own hash
  // and equality (out of line: their calls made every look-up save and restore registers).
  std::uint64_t hashKey(NodeId node, const Value* key, KeySpec spec) const;
  bool keyEqual(FactRef f, const Value* key, KeySpec spec) const;
  // The same for index x's key, inline: its integer keys compare as bits with no call (an
  // out-of-line keyEqual was 40 instructions a compare on new-heat-transfer's updates and joins).
  bool keyEqualIn(std::uint32_t x, FactRef f, const Value* key) const {
    const Index& ix = indexes_[x];
    return ix.integer ? bitsEqual(f, key, ix.key) : keyEqualOfTypes(f, key, ix.key);
  }

 private:
  struct Index {
    KeySpec key;
    SlotHash heads;
    bool integer = false;  // integerKey(key): firstWithKey hashes and compares the bits inline
  };
  // Integer-like keys (their bits are their identity): key_hash.hpp, shared with native code.
  static std::uint64_t integerHash(NodeId node, const Value* key, std::uint32_t count) {
    std::uint64_t h = key_hash::start(node);
    for (std::uint32_t i = 0; i < count; ++i) h = key_hash::addField(h, key[i].bits());
    return key_hash::finish(h);
  }
  // The first fact with this key in index `index` (kNoFact if none), and the key's hash.
  [[gnu::always_inline]] FactRef findKey(NodeId n, std::uint32_t index, const Value* key,
                                         std::uint64_t& hash) const {
    const Index& x = indexes_[index];
    return withKey(x, n, key, [&](std::uint64_t h, auto&& eq) {
      hash = h;
      return x.heads.find(h, eq);
    });
  }
  // probe(hash, eq) with the key's hash and the test of a stored fact g against it (node and key
  // fields): integer keys (pagerank's neighbour, every ITER_KEY on a node) hashed and compared as
  // bits inline, the others through the types. The one place that chooses; look-ups and
  // linkIndexes probe through it.
  template <class Probe>
  [[gnu::always_inline]] FactRef withKey(const Index& x, NodeId n, const Value* key, Probe&& probe) const {
    const KeySpec spec = x.key;
    if (x.integer)
      return probe(integerHash(n, key, spec.count),
                   [&](std::uint32_t g) { return node(g) == n && bitsEqual(g, key, spec); });
    return probe(hashKey(n, key, spec),
                 [&](std::uint32_t g) { return node(g) == n && keyEqual(g, key, spec); });
  }
  bool bitsEqual(FactRef f, const Value* key, KeySpec spec) const {
    const Value* a = args(f) + spec.first;
    for (std::uint32_t i = 0; i < spec.count; ++i)
      if (a[i].bits() != key[i].bits()) return false;
    return true;
  }

  bool integerKey(KeySpec spec) const {
    if (spec.first + spec.count > 32) return false;
    const std::uint64_t m = ((std::uint64_t(1) << spec.count) - 1) << spec.first;
    return (integerFields_ & m) == m;
  }
  [[gnu::noinline]] std::uint64_t hashKeyOfTypes(NodeId node, const Value* key, KeySpec spec) const;
  [[gnu::noinline]] bool keyEqualOfTypes(FactRef f, const Value* key, KeySpec spec) const;

  std::size_t base(FactRef f) const { return std::size_t(f) * stride_; }
  std::size_t linkWord(FactRef f, std::uint32_t index) const { return base(f) + indexLinkWord(index); }
  std::uint32_t lo(std::size_t w) const { return std::uint32_t(words_[w].bits()); }
  std::uint32_t hi(std::size_t w) const { return std::uint32_t(words_[w].bits() >> 32); }
  void setLo(std::size_t w, std::uint32_t v) {
    words_[w] = Value::fromBits((words_[w].bits() & 0xFFFFFFFF00000000ull) | v);
  }
  void setHi(std::size_t w, std::uint32_t v) {
    words_[w] = Value::fromBits((words_[w].bits() & 0xFFFFFFFFull) | (std::uint64_t(v) << 32));
  }
  FactRef prevOf(FactRef f) const { return lo(base(f)); }
  // Stores a fact in the taken slot f and links it into the list between p and nx. (A fresh slot
  // is not zeroed: the two connects write both halves of its link word.)
  void fill(ListHead& list, FactRef f, NodeId n, const Value* args, std::uint32_t count, FactRef p,
            FactRef nx) {
    Value* w = words_.data() + base(f);
    copyArgs(w + argOffset_, args, arity());
    w[1] = Value::fromBits((std::uint64_t(count) << 32) | n);
    connect(list, p, f);
    connect(list, f, nx);
    ++list.size;
    ++live_;
  }
  // A fact's arguments, one store each for the few of most facts (a loop took 13 instructions a
  // fact heat-transfer's nodes send each other).
  static void copyArgs(Value* to, const Value* from, std::uint32_t n) {
    switch (n) {
      case 3:
        to[2] = from[2];
        [[fallthrough]];
      case 2:
        to[1] = from[1];
        [[fallthrough]];
      case 1:
        to[0] = from[0];
        [[fallthrough]];
      case 0:
        return;
      default:
        for (std::uint32_t i = 0; i < n; ++i) to[i] = from[i];
    }
  }
  // p and nx become neighbours in the list (kNoFact: that end of the list): linking a fact f in
  // between is connect(p, f) and connect(f, nx); taking it out, connect(p, nx).
  void connect(ListHead& list, FactRef p, FactRef nx) {
    if (p == kNoFact)
      list.first = nx;
    else
      setHi(base(p), nx);
    if (nx == kNoFact)
      list.last = p;
    else
      setLo(base(nx), p);
  }

  FactRef chainHead(FactRef f, std::uint32_t x, std::uint64_t& hash) const;
  // Hash of a node and all arguments, for the de-duplication table. A derivation hashes the same
  // key for find and then insert (or erase): the last result is remembered.
  std::uint64_t dedupHash(NodeId node, const Value* key) const;
  // Links f into its index chains; for index 0 the chain head and key hash may be known already.
  void linkIndexes(FactRef f, std::uint32_t fromIndex = 0);
  void linkIndex(FactRef f, std::uint32_t x, FactRef head, std::uint64_t hash);
  // f at the end of head's chain in index x (head kNoFact: a chain of its own, hashed by the caller).
  void chainAtEnd(FactRef f, std::uint32_t x, FactRef head);
  void growFor(std::size_t facts);  // room for that many more slots, growing by a quarter when full
  const Value* grownForOneMore(const Value* a);  // growFor(1), `a` re-pointed if it was in the table
  FactRef place(ListHead& list, NodeId n, const Value* a, std::uint32_t cnt, FactRef after,
                bool adopt = false);
  void unlinkIndexes(FactRef f);
  void unhash(FactRef f);  // out of its index chains and the de-duplication table
  void unlinkIndex(FactRef f, std::uint32_t x);
  // Links f into chain x in front of the next fact of the list with its key (at the end if none).
  void linkInListOrder(const ListHead& list, FactRef f, std::uint32_t x);
  static constexpr std::uint32_t kMaxIndexes = 64;  // replaceArgs keeps one bit per index
  void replaceIndexedArgs(const ListHead& list, FactRef f, const Value* args);
  void retainArgs(const Value* args) { references_.retain(heap_, args); }
  void releaseArgs(FactRef f) { references_.release(heap_, args(f)); }

  const TypeTable& types_;
  Heap& heap_;
  std::vector<TypeId> fields_;
  ReferenceFields references_;  // the fields to retain/release (boxed, counted nodes)
  std::vector<Index> indexes_;
  // Slots whose pages releaseFreePages gave back, [first, end) ranges (nullptr: none yet). (The
  // flags below sit after live_, in what was padding.)
  struct SlotRange {
    FactRef first, end;
  };
  std::unique_ptr<std::vector<SlotRange>> released_;
  SlotHash facts_;                               // de-duplication: node + all arguments
  static constexpr std::uint32_t kHashMemo = 4;  // arities up to this use the memo
  mutable NodeId memoNode_ = 0xFFFFFFFFu;
  // Bit i: field i (i < 32) is an int, bool, node or thread. 32 bits, in the padding before
  // memoKey_: a larger FactTable made indexing the Database's vector of them dearer everywhere
  // (heat-transfer 20x20 +2 % instructions with a 64-bit mask after allUnboxed_).
  std::uint32_t integerFields_ = 0;
  mutable Value memoKey_[kHashMemo] = {};
  mutable std::uint64_t memoHash_ = 0;
  std::uint32_t stride_ = 0, argOffset_ = 0;
  LargeBuffer<Value> words_;
  const Value* slotArray_ = nullptr;  // words_.data(), refreshed whenever words_ reallocates
  FactRef freeList_ = kNoFact;
  std::uint32_t slots_ = 0;  // words_.size() / stride_
  std::uint32_t live_ = 0;
  bool allUnboxed_ = true;  // no field is a pointer
  bool dedup_;
  bool plain_ = false;  // no index and no de-duplication (insertAdopted's fast case)
  // Indexes on one field each, no de-duplication, no reference (wordsUnderIndexes): an update
  // that keeps every key relinks nothing (replaceArgs' second case).
  bool keyedWords_ = false;
  // references_.pattern(): what erase releases, in one load (in the padding: still 256 bytes).
  std::int8_t referencePattern_ = ReferenceFields::kNoReferences;
};

}  // namespace meldvm
