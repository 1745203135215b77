// The inputs of an aggregated predicate whose group is the node alone (aggregate on the first
// field, spec §4.1.2), kept per node in one contiguous run of records, in insertion order.
//
// Why not a FactTable: every fact arriving for such a predicate is an aggregate input, and a
// FactTable finds it through a hash table shared by all nodes and links it into a list of slots
// scattered over the table: three or four cache misses and a few hundred instructions per input.
// A node's inputs are few (about its in-degree), so scanning one run of records finds an input in
// a cache line or two. A group with very many inputs pays a linear scan per change; a `sum` already
// rescans its group on every change.
//
// Record layout, in 8-byte words: [count] then the arguments (home excluded). Runs live in one
// word array, in size classes of 2, 4, 8, ... records recycled through per-class free lists, so
// the steady state allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/heap.hpp"
#include "meldvm/large_allocator.hpp"
#include "meldvm/reference_fields.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

class GroupInputs {
 public:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

  GroupInputs(const TypeTable& types, Heap& heap, std::vector<TypeId> fields);
  ~GroupInputs();  // releases the boxed arguments still stored
  GroupInputs(GroupInputs&&) = default;

  void addNodes(std::uint32_t count) { runs_.resize(runs_.size() + count); }
  std::uint32_t size(NodeId n) const { return runs_[n].size; }
  // The position of the input with exactly these arguments at node n, or kNone.
  std::uint32_t find(NodeId n, const Value* args) const {
    if (stride_ == 2 && integerKeys_) return findWord(n, args[0].bits());
    return findAny(n, args);
  }
  // Valid until the next append (the word array may move).
  const Value* args(NodeId n, std::uint32_t i) const { return record(n, i) + 1; }
  std::uint32_t count(NodeId n, std::uint32_t i) const { return std::uint32_t(record(n, i)[0].bits()); }
  void setCount(NodeId n, std::uint32_t i, std::uint32_t count) {
    words_[runs_[n].offset + std::size_t(i) * stride_] = Value::fromBits(count);
  }
  // Adds an input at the end of the node's run; its boxed arguments are retained.
  void append(NodeId n, const Value* args, std::uint32_t count);
  // Removes the input at position i (later inputs move up one place); its boxed arguments are
  // released.
  void erase(NodeId n, std::uint32_t i);
  // Removes the input at position i, moving the last input into its place: for groups whose
  // order does not matter (an int min or max), it saves moving every later input.
  void eraseUnordered(NodeId n, std::uint32_t i);
  void clear(NodeId n);

  // The same for a group of one int field (records [count][value], nothing to retain): the
  // shape of `p(node, min int)`, whose inputs arrive by the tens of millions (B2 shortest-path:
  // inline, without the general case's calls, moves and releases, its native run takes 8 % fewer
  // instructions).
  std::uint32_t findInt(NodeId n, std::int32_t x) const { return findWord(n, Value::fromInt(x).bits()); }
  std::int32_t intAt(NodeId n, std::uint32_t i) const { return record(n, i)[1].asInt(); }
  void appendInt(NodeId n, std::int32_t x, std::uint32_t count) {
    Run& r = runs_[n];
    if (r.sizeClass == kNone || r.size == (std::uint32_t(2) << r.sizeClass)) [[unlikely]] {
      const Value v = Value::fromInt(x);
      append(n, &v, count);
      return;
    }
    Value* rec = words_.data() + r.offset + std::size_t(r.size) * 2;
    rec[0] = Value::fromBits(count);
    rec[1] = Value::fromInt(x);
    ++r.size;
  }
  void eraseIntUnordered(NodeId n, std::uint32_t i) {
    Run& r = runs_[n];
    Value* run = words_.data() + r.offset;
    const std::size_t last = std::size_t(r.size - 1) * 2;
    run[std::size_t(i) * 2] = run[last];
    run[std::size_t(i) * 2 + 1] = run[last + 1];
    dropLast(r);
  }
  // Hints that node n's inputs are read soon: first where its run is, then the run (always inlined: GCC drops
  // calls to functions whose only effect is a prefetch).
  [[gnu::always_inline]] void prefetchRun(NodeId n) const { __builtin_prefetch(&runs_[n]); }
  [[gnu::always_inline]] void prefetch(NodeId n) const {
    if (runs_[n].size != 0) __builtin_prefetch(words_.data() + runs_[n].offset);
  }
  std::size_t bytesReserved() const {
    return words_.capacity() * sizeof(Value) + runs_.capacity() * sizeof(Run);
  }

 private:
  struct Run {
    std::uint32_t offset = 0;         // first word in words_
    std::uint32_t size = 0;           // records in use
    std::uint32_t sizeClass = kNone;  // capacity 2 << sizeClass records; kNone: no run yet
  };
  const Value* record(NodeId n, std::uint32_t i) const {
    return words_.data() + runs_[n].offset + std::size_t(i) * stride_;
  }
  // One integer-like field: records of two words, [count][value]; four compared per step.
  std::uint32_t findWord(NodeId n, std::uint64_t key) const {
    const Run& r = runs_[n];
    const Value* rec = words_.data() + r.offset + 1;
    std::uint32_t i = 0;
    for (; i + 4 <= r.size; i += 4, rec += 8)
      if (int(rec[0].bits() == key) | int(rec[2].bits() == key) | int(rec[4].bits() == key) |
          int(rec[6].bits() == key))
        return rec[0].bits() == key ? i : rec[2].bits() == key ? i + 1 : rec[4].bits() == key ? i + 2 : i + 3;
    for (; i < r.size; ++i, rec += 2)
      if (rec[0].bits() == key) return i;
    return kNone;
  }
  std::uint32_t findAny(NodeId n, const Value* args) const;
  std::uint32_t allocate(std::uint32_t sizeClass);  // returns the first word of a free run
  void free(std::uint32_t offset, std::uint32_t sizeClass);
  // Releases the boxed arguments of input i; returns its record (the gap to fill).
  Value* releaseRecord(const Run& r, std::uint32_t i);
  void dropLast(Run& r) {  // one record fewer; an emptied run is given back
    if (--r.size == 0) [[unlikely]]
      giveBack(r);
  }
  void giveBack(Run& r);

  const TypeTable& types_;
  Heap& heap_;
  std::vector<TypeId> fields_;
  ReferenceFields references_;  // the fields to retain/release
  bool integerKeys_ = true;     // every field compares by its bits
  std::uint32_t stride_;
  LargeBuffer<Value> words_;
  std::vector<std::uint32_t> freeRuns_;  // per size class: the first word of a free run, or kNone
  std::vector<Run> runs_;
  std::vector<Value> scratch_;  // an appended input's arguments while its run moves
};

}  // namespace meldvm
