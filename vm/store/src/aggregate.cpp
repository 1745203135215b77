// Aggregated persistent predicates (spec §4.1.2, §6.8). Every input is kept (a multiset grouped by
// the fields before the aggregate field); each change of a group recomputes the group's value at
// once ("eager", the only mode cl-meld emits) and, when the visible fact differs from the published
// one, retracts the old fact and asserts the new one. The caller gets both in the Change, to run
// the persistent processes in negative then positive mode.
//
// Inputs live in one of two stores with one interface (the adapters below): a GroupInputs run per
// node when the group is the node alone, or a FactTable grouped through its index 0 when the
// group has key fields.
#include <algorithm>

#include "meldvm/database.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

namespace {

// The inputs of one node's group when the group is the node (aggregate on the first field).
struct NodeGroup {
  using Handle = std::uint32_t;
  static constexpr Handle kEnd = GroupInputs::kNone;
  GroupInputs& in;
  NodeId n;
  Handle find(const Value* a) const { return in.find(n, a); }
  Handle first() const { return in.size(n) != 0 ? 0 : kEnd; }
  Handle next(Handle h) const { return h + 1 < in.size(n) ? h + 1 : kEnd; }
  const Value* args(Handle h) const { return in.args(n, h); }
  std::uint32_t count(Handle h) const { return in.count(n, h); }
  void setCount(Handle h, std::uint32_t c) { in.setCount(n, h, c); }
  void insert(const Value* a, std::uint32_t c) { in.append(n, a, c); }
  void erase(Handle h) { in.erase(n, h); }
};

// The inputs of a group keyed by the fields before the aggregate field (index 0 of the table).
struct KeyedGroup {
  using Handle = FactRef;
  static constexpr Handle kEnd = kNoFact;
  FactTable& in;
  ListHead& list;
  NodeId n;
  const Value* key;  // the input being changed (its key fields name the group)
  Handle find(const Value* a) const { return in.find(n, a); }
  Handle first() const { return in.firstWithKey(n, 0, key); }
  Handle next(Handle h) const { return in.nextWithKey(0, h); }
  const Value* args(Handle h) const { return in.args(h); }
  std::uint32_t count(Handle h) const { return in.count(h); }
  void setCount(Handle h, std::uint32_t c) { in.setCount(h, c); }
  void insert(const Value* a, std::uint32_t c) { in.insert(list, n, a, c); }
  void erase(Handle h) { in.erase(list, h); }
};

}  // namespace

template <class Group>
bool Database::computeAggregate(PredId p, const Group& g) {
  const PredicateDesc& d = preds_[p];
  const TypeTable& types = heap_.types();
  const std::uint32_t k = d.aggregateField;
  const TypeId ft = d.fields[k];
  const auto firstInput = g.first();
  if (firstInput == Group::kEnd) return false;

  // Fields after the aggregate field come from the winning input (min/max) or from the first input
  // in store order (first/sum); ties keep the earliest input.
  auto winner = firstInput;
  Value sum;
  if (d.aggregate == AggregateKind::Min || d.aggregate == AggregateKind::Max) {
    const int better = d.aggregate == AggregateKind::Min ? -1 : 1;
    for (auto f = g.next(firstInput); f != Group::kEnd; f = g.next(f))
      if (compareValuesFast(types, ft, g.args(f)[k], g.args(winner)[k]) * better > 0) winner = f;
  } else if (d.aggregate == AggregateKind::Sum) {
    // A sum over the multiset: an input stored with count c counts c times.
    if (types.kind(ft) == TypeKind::Int) {
      std::uint32_t total = 0;  // 32-bit wrap-around like the established VM's int arithmetic
      for (auto f = firstInput; f != Group::kEnd; f = g.next(f))
        total += std::uint32_t(g.args(f)[k].asInt()) * g.count(f);
      sum = Value::fromInt(std::int32_t(total));
    } else if (types.kind(ft) == TypeKind::Float) {
      double total = 0.0;
      for (auto f = firstInput; f != Group::kEnd; f = g.next(f))
        for (std::uint32_t c = 0; c < g.count(f); ++c) total += g.args(f)[k].asFloat();
      sum = Value::fromFloat(total);
    } else {  // list float: element-wise, as long as the shortest list (like addfloatlists)
      std::size_t len = SIZE_MAX;
      for (auto f = firstInput; f != Group::kEnd; f = g.next(f)) {
        std::size_t l = 0;
        for (Value v = g.args(f)[k]; !v.isNil(); v = listTail(v)) ++l;
        len = std::min(len, l);
      }
      sums_.assign(len, 0.0);
      for (auto f = firstInput; f != Group::kEnd; f = g.next(f))
        for (std::uint32_t c = 0; c < g.count(f); ++c) {
          Value v = g.args(f)[k];
          for (std::size_t i = 0; i < len; ++i, v = listTail(v)) sums_[i] += listHead(v).asFloat();
        }
      sumItems_.clear();
      for (double s : sums_) sumItems_.push_back(Value::fromFloat(s));
      sumList_ = heap_.makeList(ft, sumItems_);
      sum = sumList_;
    }
  }
  setValues(next_, g.args(winner), d.arity());
  if (d.aggregate == AggregateKind::Sum) next_[k] = sum;
  return true;
}

Change Database::aggregateChange(NodeId n, PredId p, const Value* args, std::uint32_t copies, bool add) {
  if (intMinMax_[p]) return intMinMaxChange(n, p, args[0], copies, add);
  const PredicateDesc& d = preds_[p];
  // Our own reference to the input: `args` may point into a fact that this change erases.
  setValues(input_, args, d.arity());
  if (!references_[p].empty()) {
    references_[p].retain(heap_, input_.data());
    inputPred_ = p;
    holdsInput_ = true;
  }
  if (d.aggregateField == 0)
    return aggregateChangeIn(n, p, NodeGroup{nodeInputs_[groupInputs_[p]], n}, copies, add);
  const std::uint32_t it = inputTable_[p];
  return aggregateChangeIn(n, p, KeyedGroup{tables_[it], head(n, it), n, input_.data()}, copies, add);
}

template <class Group>
Change Database::aggregateChangeIn(NodeId n, PredId p, Group g, std::uint32_t copies, bool add) {
  const PredicateDesc& d = preds_[p];
  const TypeTable& types = heap_.types();
  Change c;
  const auto f = g.find(input_.data());
  FactTable& visible = tables_[p];
  const FactRef old = d.aggregateField == 0 ? head(n, p).first : visible.firstWithKey(n, 0, input_.data());
  // min/max/first change the visible fact only when the winner changes, which most inputs do
  // not do: decide that from the published value instead of rescanning the group. Ties keep the
  // earliest input, so an input equal to the published value never wins.
  const bool selects = d.aggregate != AggregateKind::Sum;
  const std::uint32_t k = d.aggregateField;
  const int better = d.aggregate == AggregateKind::Max ? 1 : -1;
  auto rank = [&](const Value* a) {  // > 0: a beats the published value
    if (d.aggregate == AggregateKind::First) return -1;
    return compareValuesFast(types, d.fields[k], a[k], visible.args(old)[k]) * better;
  };
  bool rescan = true;
  if (add) {
    if (f != Group::kEnd) {
      g.setCount(f, g.count(f) + copies);
      c.count = g.count(f);
      if (selects && old != kNoFact) return c;  // one more copy of a stored input: same winner
    } else {
      g.insert(input_.data(), copies);
      c.count = copies;
    }
    if (selects && old != kNoFact) {
      if (rank(input_.data()) <= 0) return c;
      setValues(next_, input_.data(), input_.size());  // the new input is the new winner
      rescan = false;
    }
  } else {
    if (f == Group::kEnd) {
      c.found = false;
      return c;
    }
    if (g.count(f) > copies) {
      g.setCount(f, g.count(f) - copies);
      c.count = g.count(f);
      if (selects && old != kNoFact) return c;
    } else {
      // An input worse than the published value was not the winner (for first: one that is
      // not the first input), so removing it changes nothing.
      const bool wasWinnerCandidate =
          old == kNoFact || d.aggregate == AggregateKind::Sum ||
          (d.aggregate == AggregateKind::First ? g.first() == f : rank(input_.data()) >= 0);
      g.erase(f);
      if (!wasWinnerCandidate) return c;
    }
  }

  const bool has = rescan ? computeAggregate(p, g) : true;
  if (old != kNoFact && has) {
    bool same = true;
    for (std::uint32_t i = 0; i < d.arity() && same; ++i)
      same = valuesEqualFast(types, d.fields[i], visible.args(old)[i], next_[i]);
    if (same) return c;
  }
  if (old != kNoFact) {
    keepRemoved(p, old);
    visible.erase(head(n, p), old);
    c.removed = true;
    c.removedArgs = removed_;
  }
  if (has) {
    visible.insert(head(n, p), n, next_.data(), 1);
    setValues(added_, next_.data(), next_.size());
    c.added = true;
    c.addedArgs = added_;
  }
  return c;
}

// The common shape `type p(node, min int)` (or max): the input is the value itself, so the group
// is a set of distinct ints with counts and the published fact is the best of them. The same
// outcome as aggregateChangeIn, without the generic machinery (B2 shortest-path sends tens of
// millions of such inputs).
Change Database::intMinMaxChange(NodeId n, PredId p, Value v, std::uint32_t copies, bool add) {
  GroupInputs& g = nodeInputs_[groupInputs_[p]];
  ListHead& list = head(n, p);
  const FactRef old = list.first;
  const bool min = intMinMax_[p] == kIntMin;
  const std::int32_t x = v.asInt();
  auto beats = [min](std::int32_t a, std::int32_t b) { return min ? a < b : a > b; };
  auto published = [&] { return tables_[p].args(old)[0].asInt(); };
  const std::uint32_t i = g.findInt(n, x);
  Change c;
  std::int32_t best = x;
  bool has = true;
  if (add) {
    if (i != GroupInputs::kNone) {
      c.count = g.count(n, i) + copies;
      g.setCount(n, i, c.count);
      if (old != kNoFact) return c;  // one more copy of a stored input: same winner
    } else {
      g.appendInt(n, x, copies);
      c.count = copies;
    }
    if (old != kNoFact && !beats(x, published())) return c;
  } else {
    if (i == GroupInputs::kNone) {
      c.found = false;
      return c;
    }
    if (g.count(n, i) > copies) {
      c.count = g.count(n, i) - copies;
      g.setCount(n, i, c.count);
      if (old != kNoFact) return c;
    } else {
      // Only the published value's input can change the winner when it goes.
      const bool wasWinner = old == kNoFact || x == published();
      g.eraseIntUnordered(n, i);  // equal ints are interchangeable: the order of inputs is not seen
      if (!wasWinner) return c;
    }
    has = g.size(n) != 0;
    if (has) {
      best = g.intAt(n, 0);
      for (std::uint32_t k = 1; k < g.size(n); ++k)
        if (beats(g.intAt(n, k), best)) best = g.intAt(n, k);
      if (old != kNoFact && best == published()) return c;
    }
  }
  publishIntMinMax(n, p, list, has, best, c);
  return c;
}

// The winner changed: the old published fact goes, the new one (if any input is left) comes.
void Database::publishIntMinMax(NodeId n, PredId p, ListHead& list, bool has, std::int32_t best, Change& c) {
  FactTable& visible = tables_[p];
  if (const FactRef old = list.first; old != kNoFact) {
    keepRemoved(p, old);
    visible.erase(list, old);
    c.removed = true;
    c.removedArgs = removed_;
  }
  if (has) {
    const Value b = Value::fromInt(best);
    visible.insert(list, n, &b, 1);
    setValues(added_, &b, 1);
    c.added = true;
    c.addedArgs = added_;
  }
}

}  // namespace meldvm
