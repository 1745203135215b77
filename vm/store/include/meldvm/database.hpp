// The databases of all nodes (spec §6.3): per node and predicate, linear facts in insertion order,
// persistent facts with counts, aggregated persistent predicates kept eagerly with retraction
// (§6.8), and optional per-field indexes. Storage is one FactTable per relation shared by all nodes
// (fact_table.hpp); per node there is only one ListHead per relation, kept node-major. The inputs
// of an aggregate grouped by the node alone live in a GroupInputs (one run of records per node).
//
// The Database stores and reports; it does not run rules. derive/retract return a Change saying
// which visible fact appeared or disappeared, so that the rule engine can run the persistent
// processes in positive or negative mode (§6.5, §6.8).
//
// Lifetime: the Heap and the PredicateTable must outlive the Database. Argument pointers returned
// by args() stay valid until the next insertion into the same predicate.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "meldvm/fact_table.hpp"
#include "meldvm/group_inputs.hpp"
#include "meldvm/heap.hpp"
#include "meldvm/large_allocator.hpp"
#include "meldvm/node_heads.hpp"
#include "meldvm/predicate.hpp"
#include "meldvm/reference_fields.hpp"

namespace meldvm {

struct Change {
  bool found = true;        // retract: the fact (or aggregate input) was stored
  bool added = false;       // a visible fact appeared: count 0 -> 1, or a new aggregate value
  bool removed = false;     // a visible fact disappeared: count -> 0, or an aggregate value replaced
  std::uint32_t count = 0;  // copies of the derived/retracted fact (or aggregate input) afterwards
  // Arguments of the appeared / disappeared visible fact; valid until the next change of the
  // database (the disappeared fact's boxed values are kept alive until then).
  std::span<const Value> addedArgs, removedArgs;
};

class Database {
 public:
  Database(const PredicateTable& preds, Heap& heap);
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;
  ~Database();

  // Nodes are numbered densely from 0. addNodes returns the first new id.
  NodeId addNodes(NodeId count);
  NodeId nodeCount() const { return NodeId(alive_.size()); }
  // Until a node is removed every node is alive: no look-up in the byte array, whose random reads
  // (one per message sent) are a cache miss each on large graphs.
  bool alive(NodeId n) const { return removedNodes_ == 0 || alive_[n] != 0; }
  // For native code: the address of a bound below which every node exists and is alive.
  const std::uint32_t* liveBelowAddress() const { return &liveBelow_; }
  // Drops every fact of the node (created nodes collected by the GC, §6.10); the dump skips it.
  void removeNode(NodeId n);
  // Whether p's facts hold references (a boxed field, or a node the Heap counts): copies of its
  // arguments are retained and released (referenceFields).
  bool holdsReferences(PredId p) const { return referencePattern_[p] != ReferenceFields::kNoReferences; }
  // ReferenceFields::pattern of p's fields, in one load (copying arguments fact by fact).
  std::int8_t referencePattern(PredId p) const { return referencePattern_[p]; }
  // Those fields, to retain or release a copy of p's arguments held elsewhere (a message).
  const ReferenceFields& referenceFields(PredId p) const { return references_[p]; }
  // A removed node comes back, with no facts (a created node's id used again).
  void reviveNode(NodeId n);
  // Drops every fact of the node, which stays alive (a node that moved to another store).
  void clearNode(NodeId n);
  // What the node stores, as the facts to store again elsewhere to rebuild it: linear facts in
  // list order, persistent facts in store order with their copies, and for an aggregated
  // predicate its inputs (not its values). f(PredId, const Value* args, std::uint32_t copies).
  template <class F>
  void forEachStored(NodeId n, F&& f) const {
    for (PredId p = 0; p < preds_.size(); ++p) {
      if (preds_[p].action) continue;
      if (const std::uint32_t g = groupInputs_[p]; g != kNoTable) {
        const GroupInputs& in = nodeInputs_[g];
        for (std::uint32_t i = 0; i < in.size(n); ++i) f(p, in.args(n, i), in.count(n, i));
        continue;
      }
      const std::uint32_t t = inputTable_[p] != kNoTable ? inputTable_[p] : p;
      for (FactRef x = head(n, t).first; x != kNoFact; x = tables_[t].next(x))
        if (tables_[t].count(x) != 0) f(p, tables_[t].args(x), preds_[p].linear ? 1u : tables_[t].count(x));
    }
  }

  // An index on one field (home excluded), for `index p/N` or wherever match plans look facts up
  // by a bound field. Must be requested before any fact of the predicate is stored. Idempotent;
  // returns the index handle for firstWithKey.
  std::uint32_t requestIndex(PredId p, std::uint32_t field);

  // Memory held by the store: fact tables, their hash tables, the per-node list heads.
  std::size_t bytesReserved() const { return tableBytes() + headBytes(); }
  std::size_t tableBytes() const {
    std::size_t b = 0;
    for (const FactTable& t : tables_) b += t.bytesReserved();
    for (const GroupInputs& g : nodeInputs_) b += g.bytesReserved();
    return b;
  }
  std::size_t headBytes() const { return heads_.bytesReserved() + alive_.capacity(); }
  // FactTable::releaseFreePages on every table (a shard that gave nodes away); the bytes given back.
  std::size_t releaseFreePages() {
    std::size_t b = 0;
    for (FactTable& t : tables_) b += t.releaseFreePages();
    return b;
  }
  // Room for that many facts of p (all nodes together) without growing.
  void reserve(PredId p, std::size_t facts) { tables_[p].reserve(facts); }

  // Linear predicates.
  // adopt: the caller's references to the boxed arguments go to the stored fact (no retain).
  FactRef addLinear(NodeId n, PredId p, const Value* args, bool adopt = false);
  void consume(NodeId n, PredId p, FactRef f);  // read next(p, f) first when iterating
  // The same for the rule engine, which knows that p is a linear predicate and n a live node (the
  // bytecode's verifier and the engine's own bookkeeping say so): no checks, inline, and the
  // engine's references to the arguments go to the fact. (The checks and the calls were a third
  // of what storing a fact cost.)
  FactRef addLinearTrusted(NodeId n, PredId p, const Value* args) {
    releaseHeldScratch();
    return tables_[p].insertAdopted(head(n, p), n, args);
  }
  // The same for a caller that stores many facts (Machine::storeSentLinear): it releases the held
  // scratch once before (releaseHeldScratch) and looks the node's heads up once
  // (listHeadsForWrite), for the fact and for the rules it wakes.
  FactRef addLinearTrustedAt(ListHead* heads, NodeId n, PredId p, const Value* args) {
    return tables_[p].insertAdopted(heads[p], n, args);
  }
  ListHead* listHeadsForWrite(NodeId n) { return heads_.forWrite(n); }
  // What an aggregate's evaluation left the store holding (values of retracted or summed
  // inputs), released before the store changes.
  void releaseHeldScratch() {
    if (holdsRemoved_ || holdsInput_ || !sumList_.isNil()) [[unlikely]]
      releaseScratch();
  }
  void consumeTrusted(NodeId n, PredId p, FactRef f) {
    releaseHeldScratch();
    tables_[p].erase(head(n, p), f);
  }
  // A consumed fact stays linked until the rule run ends (so that loops can step past it); the
  // mark (a count of 0) tells iterations to skip it. consume() unlinks it later.
  void markConsumed(PredId p, FactRef f) { tables_[p].setCount(f, 0); }
  bool consumedMark(PredId p, FactRef f) const { return tables_[p].count(f) == 0; }
  // In-place update (§6.4.5): new arguments; the fact keeps its list position unless moveToBack.
  void updateLinear(NodeId n, PredId p, FactRef f, const Value* args, bool moveToBack);
  // The same for the rule engine, which updates only facts its loops found (inline: heat-transfer
  // updates a fact for every message it takes in).
  void updateLinearTrusted(NodeId n, PredId p, FactRef f, const Value* args, bool moveToBack) {
    releaseHeldScratch();
    FactTable& t = tables_[p];
    ListHead& list = head(n, p);
    if (moveToBack) t.moveToBack(list, f);
    t.replaceArgs(list, f, args);
  }

  // Persistent predicates, aggregated ones included (then args is an aggregate input).
  Change derive(NodeId n, PredId p, const Value* args, std::uint32_t copies = 1);
  Change retract(NodeId n, PredId p, const Value* args, std::uint32_t copies = 1);
  // derive(n, p, f) for `count` facts of a persistent predicate that is not aggregated, stored
  // back to back in `args` (a node's literal axioms: thousands of facts at start-up, checked once
  // here instead of once each); whether any became visible.
  bool deriveEach(NodeId n, PredId p, const Value* args, std::uint32_t count);
  // derive (add) or retract one copy, for a caller that knows p is a persistent predicate and n
  // a live node (the rule engine): skips the checks and goes straight to the common aggregate
  // shape.
  Change changePersistent(NodeId n, PredId p, const Value* args, bool add) {
    if (intMinMax_[p]) {
      clearScratch();
      return intMinMaxChange(n, p, args[0], 1, add);
    }
    return add ? derive(n, p, args) : retract(n, p, args);
  }

  // Reading the visible facts of a node, in store order: linear facts in insertion order;
  // persistent facts grouped by their first field (groups in order of first appearance, facts in
  // insertion order inside a group) like the established VM's trie at its first level (§11).
  // Aggregate values: one per group, a changed value moves to the end; compact: insertion order.
  FactRef first(NodeId n, PredId p) const { return head(n, p).first; }
  const FactTable& table(PredId p) const { return tables_[p]; }  // its layout, for native code
  FactTable& tableForNativeCode(PredId p) { return tables_[p]; }  // which writes plain tables
  FactRef next(PredId p, FactRef f) const { return tables_[p].next(f); }
  const Value* args(PredId p, FactRef f) const { return tables_[p].args(f); }
  std::uint32_t copies(PredId p, FactRef f) const { return tables_[p].count(f); }
  std::uint32_t factCount(NodeId n, PredId p) const { return head(n, p).size; }  // distinct facts
  // The node's list heads, indexed by predicate (size: its distinct facts): one look-up for a
  // caller that reads several predicates of the node.
  const ListHead* listHeads(NodeId n) const { return heads_.of(n); }
  const NodeHeads& nodeHeads() const { return heads_; }  // for native code (native_abi.h)
  // The visible persistent fact with exactly these arguments, or kNoFact.
  FactRef find(NodeId n, PredId p, const Value* args) const;
  // Facts of the node whose indexed field equals key, in insertion order.
  FactRef firstWithKey(NodeId n, PredId p, std::uint32_t index, Value key) const {
    const ListHead& list = head(n, p);
    if (list.size <= kScanForKeyUpTo) return tables_[p].firstInListWithKey(list.first, index, &key);
    return tables_[p].firstWithKey(n, index, &key);
  }
  FactRef nextWithKey(PredId p, std::uint32_t index, FactRef f) const {
    return tables_[p].nextWithKey(index, f);
  }
  // A hint that node n runs soon: fetch its list heads (always inlined: GCC drops calls to
  // functions whose only effect is a prefetch).
  [[gnu::always_inline]] void prefetchNode(NodeId n) const {
    const char* p = reinterpret_cast<const char*>(heads_.of(n));
    const std::size_t bytes = tableCount_ * sizeof(ListHead);
    for (std::size_t off = 0; off < bytes; off += 64) __builtin_prefetch(p + off);
    for (const GroupInputs& g : nodeInputs_) g.prefetchRun(n);
  }
  // A hint that derive/retract(n, p, args) comes soon: fetch the hash buckets it will look at.
  [[gnu::always_inline]] void prefetchDerive(NodeId n, PredId p, const Value* args) const {
    if (const std::uint32_t g = groupInputs_[p]; g != kNoTable) {
      nodeInputs_[g].prefetch(n);
      return;
    }
    const std::uint32_t in = inputTable_[p];
    if (in == kNoTable) {
      if (!preds_[p].compact) tables_[p].prefetchFind(n, args);
      return;
    }
    tables_[in].prefetchFind(n, args);
    if (preds_[p].aggregateField > 0) {
      tables_[in].prefetchKey(n, 0, args);
      tables_[p].prefetchKey(n, 0, args);
    }
  }
  // A hint that addLinearTrusted(n, p, ...) comes soon: the list's head, then (once the head is
  // here) the last fact, whose link the new one changes.
  [[gnu::always_inline]] void prefetchListHead(NodeId n, PredId p) const {
    __builtin_prefetch(&heads_.of(n)[p], 1);
  }
  [[gnu::always_inline]] void prefetchListTail(NodeId n, PredId p) const {
    if (const FactRef last = heads_.of(n)[p].last; last != kNoFact)
      __builtin_prefetch(tables_[p].slotAddress(last), 1);
  }
  // The next stage, once the list heads are cached: the first facts of the node's lists (the
  // first two cache lines of each, which holds a few facts when they were stored together), and
  // the last fact of each longer list, which a fact appended or moved to the back links to (an
  // UPDATE's move to the back waited for it: a sixth of heat-transfer's rule that updates
  // neighbor-heat; the bytecode of heat-transfer ran 2.237 -> 2.062 s, B2 pagerank 4.761 ->
  // 4.430 s, 9 and 5 interleaved runs, 2026-11-30, 2-core AMD EPYC VM).
  [[gnu::always_inline]] void prefetchNodeFacts(NodeId n) const {
    const ListHead* h = heads_.of(n);
    for (std::size_t t = 0; t < tableCount_; ++t)
      if (h[t].first != kNoFact) {
        const char* p = reinterpret_cast<const char*>(tables_[t].slotAddress(h[t].first));
        __builtin_prefetch(p);
        __builtin_prefetch(p + 64);
        if (h[t].last != h[t].first) __builtin_prefetch(tables_[t].slotAddress(h[t].last));
      }
    for (const GroupInputs& g : nodeInputs_) g.prefetch(n);
  }
  // Distinct inputs stored for an aggregated predicate at a node.
  std::uint32_t aggregateInputs(NodeId n, PredId p) const;

  const PredicateTable& predicates() const { return preds_; }
  const TypeTable& types() const { return heap_.types(); }
  Heap& heap() const { return heap_; }

 private:
  // A node with this few facts of the predicate finds a key by walking its list: the facts are
  // read anyway, where the hash table's entry is one more miss (new-heat-transfer: 4 neighbours).
  static constexpr std::uint32_t kScanForKeyUpTo = 8;
  static constexpr std::uint32_t kNoTable = 0xFFFFFFFFu;

  const ListHead& head(NodeId n, std::uint32_t table) const { return heads_.of(n)[table]; }
  ListHead& head(NodeId n, std::uint32_t table) { return heads_.forWrite(n)[table]; }
  // Checks on every store call, inline: the failures are out of line.
  const PredicateDesc& storedPredicate(PredId p, bool linear) const {
    if (p >= preds_.size() || preds_[p].action || preds_[p].linear != linear) badPredicate(p);
    return preds_[p];
  }
  void checkNode(NodeId n) const {
    if (n >= alive_.size() || !alive(n)) badNode(n);
  }
  void noteLiveNodes() { liveBelow_ = removedNodes_ == 0 ? std::uint32_t(alive_.size()) : 0; }
  [[noreturn]] void badPredicate(PredId p) const;
  [[noreturn]] void badNode(NodeId n) const;
  // Releases what the previous Change kept alive.
  void clearScratch() {
    releaseHeldScratch();
    removed_.clear();
    added_.clear();
  }
  void releaseScratch();
  // v = a[0..n) without a library call (the scratch vectors hold a few values, reserved once).
  static void setValues(std::vector<Value>& v, const Value* a, std::size_t n) {
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = a[i];
  }
  // `copies` more of a fact of a persistent predicate that is not aggregated: a new fact (its
  // reference), or kNoFact when the fact was stored already; `count`: its copies now.
  FactRef addCopies(NodeId n, PredId p, const PredicateDesc& d, const Value* args, std::uint32_t copies,
                    std::uint32_t& count);
  void keepRemoved(PredId p, FactRef f);  // copies a visible fact into removed_ before erasing it
  Change aggregateChange(NodeId n, PredId p, const Value* args, std::uint32_t copies, bool add);
  Change intMinMaxChange(NodeId n, PredId p, Value v, std::uint32_t copies, bool add);
  void publishIntMinMax(NodeId n, PredId p, ListHead& list, bool has, std::int32_t best, Change& c);
  // The same over one of the two input stores (aggregate.cpp's NodeGroup and KeyedGroup).
  template <class Group>
  Change aggregateChangeIn(NodeId n, PredId p, Group g, std::uint32_t copies, bool add);
  // Recomputes the group's value into next_; false if the group is empty.
  template <class Group>
  bool computeAggregate(PredId p, const Group& g);

  const PredicateTable& preds_;
  Heap& heap_;
  std::vector<FactTable> tables_;            // one per predicate, then one per keyed aggregated predicate
  std::uint32_t tableCount_ = 0;             // tables_.size(), fixed once the constructor is done
  std::vector<std::uint32_t> inputTable_;    // per predicate: its keyed aggregate input table, or kNoTable
  std::vector<GroupInputs> nodeInputs_;      // the inputs of the aggregates grouped by the node alone
  std::vector<std::uint32_t> groupInputs_;   // per predicate: its entry in nodeInputs_, or kNoTable
  std::vector<ReferenceFields> references_;  // per predicate: its fields that hold references (Heap)
  std::vector<std::int8_t> referencePattern_;  // per predicate (referencePattern)
  // Per predicate: `p(node, min int)` or max (intMinMaxChange), which of the two, or neither.
  enum : std::uint8_t { kNotIntMinMax = 0, kIntMin = 1, kIntMax = 2 };
  std::vector<std::uint8_t> intMinMax_;
  NodeHeads heads_{0};                       // set up once tableCount_ is known
  std::vector<std::uint8_t> alive_;
  std::uint32_t removedNodes_ = 0;
  std::uint32_t liveBelow_ = 0;  // every node below it is alive (the node count, or 0 once one is removed)
  std::vector<std::uint8_t> grouped_;  // per predicate: new persistent facts join their first-field group

  // Scratch of the last change (reserved once, so changes allocate nothing).
  std::vector<Value> added_, removed_, input_, next_;
  PredId removedPred_ = 0, inputPred_ = 0;
  bool holdsRemoved_ = false, holdsInput_ = false;
  Value sumList_;  // a `sum list float` result built by the last change (owned reference)
  std::vector<double> sums_;
  std::vector<Value> sumItems_;
};

}  // namespace meldvm
