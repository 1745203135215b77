// Aggregated persistent predicates (spec §4.1.2, §6.8). Every input is kept (a multiset grouped by
// the fields before the aggregate field); each change of a group recomputes the group's value at
// once ("eager", the only mode cl-meld emits) and, when the visible fact differs from the published
// one, retracts the old fact and asserts the new one. The caller gets both in the Change, to run
// the persistent processes in negative then positive mode.
#include <algorithm>

#include "meldvm/database.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

bool Database::computeAggregate(NodeId n, PredId p) {
  const PredicateDesc& d = preds_[p];
  const FactTable& in = tables_[inputTable_[p]];
  const TypeTable& types = heap_.types();
  const std::uint32_t k = d.aggregateField;
  const TypeId ft = d.fields[k];
  const std::uint32_t it = inputTable_[p];
  const FactRef firstInput = groupFirst(p, it, n, input_.data());
  if (firstInput == kNoFact) return false;

  // Fields after the aggregate field come from the winning input (min/max) or from the first input
  // in store order (first/sum); ties keep the earliest input.
  FactRef winner = firstInput;
  Value sum;
  if (d.aggregate == AggregateKind::Min || d.aggregate == AggregateKind::Max) {
    const int better = d.aggregate == AggregateKind::Min ? -1 : 1;
    for (FactRef f = groupNext(p, it, firstInput); f != kNoFact; f = groupNext(p, it, f))
      if (compareValuesFast(types, ft, in.args(f)[k], in.args(winner)[k]) * better > 0) winner = f;
  } else if (d.aggregate == AggregateKind::Sum) {
    // A sum over the multiset: an input stored with count c counts c times.
    if (types.kind(ft) == TypeKind::Int) {
      std::uint32_t total = 0;  // 32-bit wrap-around like the established VM's int arithmetic
      for (FactRef f = firstInput; f != kNoFact; f = groupNext(p, it, f))
        total += std::uint32_t(in.args(f)[k].asInt()) * in.count(f);
      sum = Value::fromInt(std::int32_t(total));
    } else if (types.kind(ft) == TypeKind::Float) {
      double total = 0.0;
      for (FactRef f = firstInput; f != kNoFact; f = groupNext(p, it, f))
        for (std::uint32_t c = 0; c < in.count(f); ++c) total += in.args(f)[k].asFloat();
      sum = Value::fromFloat(total);
    } else {  // list float: element-wise, as long as the shortest list (like addfloatlists)
      std::size_t len = SIZE_MAX;
      for (FactRef f = firstInput; f != kNoFact; f = groupNext(p, it, f)) {
        std::size_t l = 0;
        for (Value v = in.args(f)[k]; !v.isNil(); v = listTail(v)) ++l;
        len = std::min(len, l);
      }
      sums_.assign(len, 0.0);
      for (FactRef f = firstInput; f != kNoFact; f = groupNext(p, it, f))
        for (std::uint32_t c = 0; c < in.count(f); ++c) {
          Value v = in.args(f)[k];
          for (std::size_t i = 0; i < len; ++i, v = listTail(v)) sums_[i] += listHead(v).asFloat();
        }
      sumItems_.clear();
      for (double s : sums_) sumItems_.push_back(Value::fromFloat(s));
      sumList_ = heap_.makeList(ft, sumItems_);
      sum = sumList_;
    }
  }
  next_.assign(in.args(winner), in.args(winner) + d.arity());
  if (d.aggregate == AggregateKind::Sum) next_[k] = sum;
  return true;
}

Change Database::aggregateChange(NodeId n, PredId p, const Value* args, std::uint32_t copies, bool add) {
  const PredicateDesc& d = preds_[p];
  const TypeTable& types = heap_.types();
  const std::uint32_t it = inputTable_[p];
  FactTable& in = tables_[it];
  // Our own reference to the input: `args` may point into a fact that this change erases.
  input_.assign(args, args + d.arity());
  for (std::size_t i = 0; i < input_.size(); ++i) heap_.retain(d.fields[i], input_[i]);
  inputPred_ = p;
  holdsInput_ = true;

  Change c;
  const FactRef f = in.find(n, input_.data());
  FactTable& visible = tables_[p];
  const FactRef old = groupFirst(p, p, n, input_.data());
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
    if (f != kNoFact) {
      in.setCount(f, in.count(f) + copies);
      c.count = in.count(f);
      if (selects && old != kNoFact) return c;  // one more copy of a stored input: same winner
    } else {
      in.insert(head(n, it), n, input_.data(), copies);
      c.count = copies;
    }
    if (selects && old != kNoFact) {
      if (rank(input_.data()) <= 0) return c;
      next_.assign(input_.begin(), input_.end());  // the new input is the new winner
      rescan = false;
    }
  } else {
    if (f == kNoFact) {
      c.found = false;
      return c;
    }
    if (in.count(f) > copies) {
      in.setCount(f, in.count(f) - copies);
      c.count = in.count(f);
      if (selects && old != kNoFact) return c;
    } else {
      // An input worse than the published value was not the winner (for first: one that is
      // not the first input), so removing it changes nothing.
      const bool wasWinnerCandidate =
          old == kNoFact || d.aggregate == AggregateKind::Sum ||
          (d.aggregate == AggregateKind::First ? groupFirst(p, it, n, input_.data()) == f
                                               : rank(input_.data()) >= 0);
      in.erase(head(n, it), f);
      if (!wasWinnerCandidate) return c;
    }
  }

  const bool has = rescan ? computeAggregate(n, p) : true;
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
    added_.assign(next_.begin(), next_.end());
    c.added = true;
    c.addedArgs = added_;
  }
  return c;
}

}  // namespace meldvm
