#include "meldvm/fact_table.hpp"

#include <algorithm>
#include <functional>
#include <stdexcept>

#include "meldvm/value_ops.hpp"

namespace meldvm {

// The Database's tables are an array that every store and look-up indexes: at 256 bytes the index
// is a shift (at 264 it took three more instructions, 2 % more of 8queens' whole run), and a
// table's hot words share cache lines with no other table's.
static_assert(sizeof(FactTable) == 256);

FactTable::FactTable(const TypeTable& types, Heap& heap, std::vector<TypeId> fields, bool dedup)
    : types_(types), heap_(heap), fields_(std::move(fields)), references_(heap_, fields_), dedup_(dedup) {
  for (TypeId t : fields_) allUnboxed_ = allUnboxed_ && !types_.boxed(t);
  referencePattern_ = references_.pattern();
  for (std::size_t i = 0; i < fields_.size() && i < 32; ++i)
    if (integerLike(types_, fields_[i])) integerFields_ |= std::uint32_t(1) << i;
  argOffset_ = 2;
  stride_ = argOffset_ + arity();
  plain_ = !dedup_;
}

FactTable::~FactTable() {
  if (references_.empty()) return;
  for (FactRef f = 0; std::size_t(f) * stride_ < words_.size(); ++f)
    if (count(f) != 0) releaseArgs(f);
}

std::uint32_t FactTable::addIndex(KeySpec key) {
  if (!words_.empty()) throw std::logic_error("meldvm: index added to a table that already holds facts");
  if (key.first + key.count > arity()) throw std::out_of_range("meldvm: index key beyond the arity");
  if (indexCount() == kMaxIndexes) throw std::length_error("meldvm: too many indexes on one predicate");
  indexes_.push_back(Index{key, {}, integerKey(key)});
  plain_ = false;
  keyedWords_ = (indexCount() == 1 || keyedWords_) && key.count == 1 && wordsUnderIndexes();
  argOffset_ = indexLinkWord(indexCount());  // the arguments follow the index links
  stride_ = argOffset_ + arity();
  return indexCount() - 1;
}

std::uint64_t FactTable::hashKey(NodeId node, const Value* key, KeySpec spec) const {
  if (!integerKey(spec)) [[unlikely]]
    return hashKeyOfTypes(node, key, spec);
  return integerHash(node, key, spec.count);
}

bool FactTable::keyEqual(FactRef f, const Value* key, KeySpec spec) const {
  if (!integerKey(spec)) [[unlikely]]
    return keyEqualOfTypes(f, key, spec);
  return bitsEqual(f, key, spec);
}

std::uint64_t FactTable::hashKeyOfTypes(NodeId node, const Value* key, KeySpec spec) const {
  std::uint64_t h = mixHash(0x6d656c64, node);
  for (std::uint32_t i = 0; i < spec.count; ++i)
    h = mixHash(h, hashValueFast(types_, fields_[spec.first + i], key[i]));
  return h;
}

bool FactTable::keyEqualOfTypes(FactRef f, const Value* key, KeySpec spec) const {
  const Value* a = args(f) + spec.first;
  for (std::uint32_t i = 0; i < spec.count; ++i)
    if (!valuesEqualFast(types_, fields_[spec.first + i], a[i], key[i])) return false;
  return true;
}

void FactTable::reserve(std::size_t facts) {
  words_.reserve(facts * stride_);
  slotArray_ = words_.data();
  if (dedup_) facts_.reserve(std::uint32_t(facts));
  for (Index& x : indexes_) x.heads.reserve(std::uint32_t(facts));
}

void FactTable::growFor(std::size_t facts) {
  // Large tables by a quarter, not the vector's doubling: a threaded run's shards each reserve
  // their share of the facts and grow when stolen nodes bring theirs, and doubling then left each
  // shard room for nearly all of them (pagerank at -j 2: 10.2 MB of slots for 5.1 MB of facts);
  // their pages move as they grow (support::growLarge: from 128 KiB), nothing is copied. Between
  // 64 KiB and 2 MiB they double: by a quarter, when tables below 2 MiB were still copied, the
  // copies of a table that grows to 2 MiB were 4 % of pagerank-recipes (the part of a mapping not
  // yet written takes no memory). Below, a quarter costs little and keeps a robot's tables small.
  if (words_.size() + facts * stride_ <= words_.capacity()) return;
  const std::size_t slots = words_.capacity() / stride_;
  const std::size_t bytes = words_.capacity() * sizeof(Value);
  const bool doubles = bytes >= 64 * 1024 && bytes < support::kHugePage;
  const std::size_t grown = slots + std::max<std::size_t>(doubles ? slots : slots / 4, 4);
  words_.reserve(std::max(grown, words_.size() / stride_ + facts) * stride_);
  slotArray_ = words_.data();
}

std::size_t FactTable::releaseFreePages() {
  const std::size_t slotBytes = std::size_t(stride_) * sizeof(Value);
  std::size_t releasedBefore = 0;
  if (released_)
    for (const SlotRange& r : *released_) releasedBefore += r.end - r.first;
  const std::size_t freeSlots = slots_ - live_ - releasedBefore;  // on the free list
  constexpr std::size_t kPage = 4096, kWorthIt = 256 * 1024;
  std::size_t given = facts_.shrink();
  for (Index& x : indexes_) given += x.heads.shrink();
  if (freeSlots * slotBytes < kWorthIt || freeSlots * 4 < slots_ ||
      words_.capacity() * sizeof(Value) < support::kMappedFrom)
    return given;
  // 1: free; 2: on a page given back now; 3: given back before
  std::vector<std::uint8_t> state(slots_, 0);
  for (FactRef f = freeList_; f != kNoFact; f = next(f)) state[f] = 1;
  if (released_)
    for (const SlotRange& r : *released_)
      for (FactRef f = r.first; f < r.end; ++f) state[f] = 3;
  const std::size_t end = std::size_t(slots_) * slotBytes / kPage * kPage;
  for (std::size_t page = 0; page < end;) {
    std::size_t run = page;  // the pages from `page` on whose slots are all free
    for (;; run += kPage) {
      if (run == end) break;
      const std::size_t first = run / slotBytes, last = (run + kPage - 1) / slotBytes;
      bool allFree = true;
      for (std::size_t f = first; f <= last && allFree; ++f) allFree = state[f] != 0;
      if (!allFree) break;
    }
    if (run > page &&
        support::discardPages(words_.data(), words_.capacity() * sizeof(Value), page, run - page)) {
      for (std::size_t f = page / slotBytes; f <= (run - 1) / slotBytes; ++f) {
        if (state[f] == 1) given += slotBytes;
        state[f] = 2;
      }
    }
    page = run == end ? end : run + kPage;
  }
  // The free list anew, lowest slots first; the released slots as ranges.
  freeList_ = kNoFact;
  std::vector<SlotRange> released;
  for (FactRef f = slots_; f-- > 0;) {
    if (state[f] == 1) {
      Value* w = words_.data() + base(f);
      w[0] = Value::fromBits(std::uint64_t(freeList_) << 32);
      freeList_ = f;
    } else if (state[f] >= 2) {
      if (!released.empty() && released.back().first == f + 1)
        released.back().first = f;
      else
        released.push_back({f, f + 1});
    }
  }
  if (!released.empty() || released_)
    released_ = std::make_unique<std::vector<SlotRange>>(std::move(released));
  return given;
}

std::uint64_t FactTable::dedupHash(NodeId n, const Value* key) const {
  // Only unboxed keys: a boxed value's bits are a pointer, which may be reused for another value.
  const std::uint32_t k = arity();
  const bool memo = k <= kHashMemo && allUnboxed_;
  if (memo && n == memoNode_) {
    bool same = true;
    for (std::uint32_t i = 0; i < k && same; ++i) same = key[i].bits() == memoKey_[i].bits();
    if (same) return memoHash_;  // equal bits are equal values of the same field types
  }
  const std::uint64_t h = hashKey(n, key, KeySpec{0, k});
  if (memo) {
    memoNode_ = n;
    for (std::uint32_t i = 0; i < k; ++i) memoKey_[i] = key[i];
    memoHash_ = h;
  }
  return h;
}

FactRef FactTable::find(NodeId n, const Value* a) const {
  const KeySpec all{0, arity()};
  return facts_.find(dedupHash(n, a), [&](std::uint32_t f) { return node(f) == n && keyEqual(f, a, all); });
}

FactRef FactTable::firstWithKey(NodeId n, std::uint32_t index, const Value* key) const {
  std::uint64_t hash;
  return findKey(n, index, key, hash);
}

// The first fact of f's chain in index x (kNoFact if none), and the key's hash in `hash`.
FactRef FactTable::chainHead(FactRef f, std::uint32_t x, std::uint64_t& hash) const {
  return findKey(node(f), x, args(f) + indexes_[x].key.first, hash);
}

void FactTable::linkIndexes(FactRef f, std::uint32_t fromIndex) {
  const NodeId n = node(f);
  for (std::uint32_t x = fromIndex; x < indexCount(); ++x) {
    Index& ix = indexes_[x];
    // The chain's head found, or f entered as a new one, in one probe of the hash table.
    const FactRef head = withKey(ix, n, args(f) + ix.key.first,
                                 [&](std::uint64_t h, auto&& eq) { return ix.heads.findOrInsert(h, eq, f); });
    chainAtEnd(f, x, head);
  }
}

void FactTable::linkIndex(FactRef f, std::uint32_t x, FactRef head, std::uint64_t h) {
  chainAtEnd(f, x, head);
  if (head == kNoFact) indexes_[x].heads.insert(h, f);
}

void FactTable::chainAtEnd(FactRef f, std::uint32_t x, FactRef head) {
  const std::size_t w = linkWord(f, x);
  setHi(w, kNoFact);
  if (head == kNoFact) {
    setLo(w, f);  // a one-fact chain: the head is its own tail
  } else {
    const std::size_t hw = linkWord(head, x);
    const FactRef tail = lo(hw);
    setHi(linkWord(tail, x), f);
    setLo(w, tail);
    setLo(hw, f);
  }
}

void FactTable::unlinkIndexes(FactRef f) {
  for (std::uint32_t x = 0; x < indexCount(); ++x) unlinkIndex(f, x);
}

void FactTable::unlinkIndex(FactRef f, std::uint32_t x) {
  const std::size_t w = linkWord(f, x);
  std::uint64_t h;
  const FactRef head = chainHead(f, x, h);
  const FactRef p = lo(w), nx = hi(w);
  if (head == f) {
    if (nx == kNoFact) {
      indexes_[x].heads.erase(h, f);
    } else {
      setLo(linkWord(nx, x), p);  // the new head points at the tail
      indexes_[x].heads.replace(h, f, nx);
    }
  } else {
    setHi(linkWord(p, x), nx);
    setLo(linkWord(nx == kNoFact ? head : nx, x), p);
  }
}

void FactTable::linkInListOrder(const ListHead& list, FactRef f, std::uint32_t x) {
  std::uint64_t h;
  const FactRef head = chainHead(f, x, h);
  // The first fact after f in the list with f's key: f goes in front of it in the chain. (A walk
  // of the list after f, only when an update changes a key: no longer than the scan of the list
  // that the established VM makes for every match.)
  FactRef g = kNoFact;
  if (head != kNoFact && list.last != f) {
    const Value* key = args(f) + indexes_[x].key.first;
    for (FactRef c = next(f); c != kNoFact && g == kNoFact; c = next(c))
      if (keyEqualIn(x, c, key)) g = c;
  }
  if (g == kNoFact) return linkIndex(f, x, head, h);
  const std::size_t w = linkWord(f, x), gw = linkWord(g, x);
  const FactRef p = lo(gw);  // g's predecessor, or the tail when g is the head
  setLo(w, p);
  setHi(w, g);
  if (g == head)
    indexes_[x].heads.replace(h, g, f);
  else
    setHi(linkWord(p, x), f);
  setLo(gw, f);
}

// `a` may point into words_ (arguments read from this very table), which growing may move: it is
// re-pointed into the new array then.
const Value* FactTable::grownForOneMore(const Value* a) {
  const Value* begin = words_.data();
  const bool inTable =
      std::greater_equal<const Value*>()(a, begin) && std::less<const Value*>()(a, begin + words_.size());
  const std::size_t off = inTable ? std::size_t(a - begin) : 0;
  growFor(1);
  return inTable ? words_.data() + off : a;
}

// Takes a slot, stores the fact and links it into the node's list (not into the hash tables).
FactRef FactTable::place(ListHead& list, NodeId n, const Value* a, std::uint32_t cnt, FactRef after,
                         bool adopt) {
  if (cnt == 0) throw std::invalid_argument("meldvm: a stored fact has a count of at least 1");
  if (!adopt && !references_.empty()) retainArgs(a);
  FactRef f;
  if (freeList_ != kNoFact) {
    f = freeList_;
    freeList_ = next(f);
  } else if (released_ && !released_->empty()) [[unlikely]] {
    SlotRange& r = released_->back();
    f = r.first++;
    if (r.first == r.end) released_->pop_back();
  } else {
    if (slots_ >= kNoFact - 1) throw std::length_error("meldvm: too many facts");
    f = slots_++;  // counted, not words_.size() / stride_: a division per new fact
    if (words_.size() + stride_ > words_.capacity()) [[unlikely]]
      a = grownForOneMore(a);
    words_.extendWithin(stride_);  // not zeroed: fill and the index links write every word
  }
  const FactRef p = after == kNoFact ? list.last : after;
  const FactRef nx = after == kNoFact ? kNoFact : next(after);
  fill(list, f, n, a, cnt, p, nx);
  return f;
}

FactRef FactTable::insert(ListHead& list, NodeId n, const Value* a, std::uint32_t cnt, FactRef after,
                          bool adopt) {
  const FactRef f = place(list, n, a, cnt, after, adopt);
  if (!indexes_.empty()) linkIndexes(f);  // (most tables have none: no call)
  if (dedup_) facts_.insert(dedupHash(n, args(f)), f);
  return f;
}

void FactTable::appendEach(ListHead& list, NodeId n, const Value* a, std::uint32_t facts) {
  if (!plain_) {  // (an index requested on a compact predicate)
    for (std::uint32_t i = 0; i < facts; ++i, a += arity()) insert(list, n, a, 1);
    return;
  }
  const Value* begin = words_.data();
  const bool inTable =  // arguments read from this very table: the array may move (place re-points)
      std::greater_equal<const Value*>()(a, begin) && std::less<const Value*>()(a, begin + words_.size());
  std::uint32_t i = 0;
  for (; i < facts && (freeList_ != kNoFact || inTable); ++i, a += arity())
    place(list, n, a, 1, kNoFact, false);
  if (i == facts) return;
  const std::uint32_t fresh = facts - i;
  if (slots_ + std::uint64_t(fresh) >= kNoFact) throw std::length_error("meldvm: too many facts");
  growFor(fresh);
  words_.extendWithin(std::size_t(fresh) * stride_);  // fill writes every word of each slot
  for (; i < facts; ++i, a += arity()) {
    if (!references_.empty()) retainArgs(a);
    const FactRef f = slots_++;
    fill(list, f, n, a, 1, list.last, kNoFact);
  }
}

FactRef FactTable::insertGrouped(ListHead& list, NodeId n, const Value* a, std::uint32_t cnt) {
  const KeySpec spec = indexes_[0].key;
  const std::uint64_t h = hashKey(n, a + spec.first, spec);
  const FactRef head = indexes_[0].heads.find(
      h, [&](std::uint32_t g) { return node(g) == n && keyEqualIn(0, g, a + spec.first); });
  const FactRef after = head == kNoFact ? kNoFact : lo(linkWord(head, 0));  // the head's prev is the tail
  const FactRef f = place(list, n, a, cnt, after);
  linkIndex(f, 0, head, h);
  linkIndexes(f, 1);
  if (dedup_) facts_.insert(dedupHash(n, args(f)), f);
  return f;
}

void FactTable::unhash(FactRef f) {
  if (!indexes_.empty()) unlinkIndexes(f);
  if (dedup_) facts_.erase(dedupHash(node(f), args(f)), f);
}

void FactTable::replaceIndexedArgs(const ListHead& list, FactRef f, const Value* a) {
  // Each chain keeps the list's order, as the established VM scans the list (an index only skips
  // the facts with other keys): a chain whose key is unchanged keeps the fact where it is, unless
  // the fact just moved to the end of the list; the others take it at its place in list order.
  std::uint64_t relink = 0;
  const bool last = list.last == f;
  for (std::uint32_t x = 0; x < indexCount(); ++x) {
    if (keyEqualIn(x, f, a + indexes_[x].key.first) && (!last || hi(linkWord(f, x)) == kNoFact)) continue;
    unlinkIndex(f, x);
    relink |= std::uint64_t(1) << x;
  }
  if (dedup_) facts_.erase(dedupHash(node(f), args(f)), f);
  retainArgs(a);  // before releasing: the new values may be the old ones
  releaseArgs(f);
  for (std::uint32_t i = 0; i < arity(); ++i) words_[base(f) + argOffset_ + i] = a[i];
  for (std::uint32_t x = 0; x < indexCount(); ++x)
    if (relink >> x & 1) linkInListOrder(list, f, x);
  if (dedup_) facts_.insert(dedupHash(node(f), args(f)), f);
}

}  // namespace meldvm
