#include "meldvm/database.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "meldvm/value_ops.hpp"

namespace meldvm {

Database::Database(const PredicateTable& preds, Heap& heap) : preds_(preds), heap_(heap) {
  const TypeTable& types = heap.types();
  std::size_t aggregated = 0, maxArity = 0;
  for (PredId p = 0; p < preds.size(); ++p) {
    aggregated += preds[p].aggregated() ? 1 : 0;
    maxArity = std::max<std::size_t>(maxArity, preds[p].arity());
  }
  // Reserved up front: FactTables never move once facts exist.
  tables_.reserve(preds.size() + aggregated);
  inputTable_.assign(preds.size(), kNoTable);
  groupInputs_.assign(preds.size(), kNoTable);
  nodeInputs_.reserve(aggregated);
  for (PredId p = 0; p < preds.size(); ++p) {
    const PredicateDesc& d = preds[p];
    const bool dedup = d.persistent() && !d.compact && !d.aggregated();
    tables_.emplace_back(types, heap, d.fields, dedup);
    // The first-field grouping of persistent facts uses an index on field 0 (also what a rule
    // asking for an index on field 0 gets).
    grouped_.push_back(dedup && d.arity() > 0);
    if (grouped_.back()) tables_.back().addIndex({0, 1});
    // Aggregated: the visible facts keep one fact per group, found through index 0 on the group
    // (or, when the group is the node alone, through the node's list: no hashing).
    if (d.aggregated() && d.aggregateField > 0) tables_.back().addIndex({0, d.aggregateField});
  }
  for (PredId p = 0; p < preds.size(); ++p) {
    const PredicateDesc& d = preds[p];
    referencePattern_.push_back(references_.emplace_back(heap_, d.fields).pattern());
    const bool intShape =
        d.aggregated() && d.aggregateField == 0 && d.arity() == 1 && types.kind(d.fields[0]) == TypeKind::Int;
    intMinMax_.push_back(!intShape                           ? kNotIntMinMax
                         : d.aggregate == AggregateKind::Min ? kIntMin
                         : d.aggregate == AggregateKind::Max ? kIntMax
                                                             : kNotIntMinMax);
    if (!d.aggregated()) continue;
    if (d.aggregateField == 0) {
      groupInputs_[p] = std::uint32_t(nodeInputs_.size());
      nodeInputs_.emplace_back(types, heap, d.fields);
      continue;
    }
    inputTable_[p] = std::uint32_t(tables_.size());
    tables_.emplace_back(types, heap, d.fields, true);  // inputs: a multiset, grouped by index 0
    tables_.back().addIndex({0, d.aggregateField});
  }
  tableCount_ = std::uint32_t(tables_.size());
  heads_ = NodeHeads(tableCount_);
  for (auto* v : {&added_, &removed_, &input_, &next_}) v->reserve(maxArity);
}

Database::~Database() { clearScratch(); }

void Database::badNode(NodeId n) const { throw std::out_of_range("meldvm: no node " + std::to_string(n)); }

void Database::badPredicate(PredId p) const {
  if (p >= preds_.size()) throw std::out_of_range("meldvm: no predicate " + std::to_string(p));
  const PredicateDesc& d = preds_[p];
  if (d.action) throw std::logic_error("meldvm: action '" + d.name + "' is executed, not stored");
  throw std::logic_error("meldvm: '" + d.name + "' is " + (d.linear ? "linear" : "persistent"));
}

NodeId Database::addNodes(NodeId count) {
  const NodeId firstNew = nodeCount();
  alive_.resize(alive_.size() + count, 1);
  noteLiveNodes();
  heads_.addNodes(count);
  for (GroupInputs& g : nodeInputs_) g.addNodes(count);
  return firstNew;
}

void Database::removeNode(NodeId n) {
  clearNode(n);
  alive_[n] = 0;
  ++removedNodes_;
  noteLiveNodes();
}

void Database::reviveNode(NodeId n) {
  if (n >= alive_.size() || alive_[n]) throw std::logic_error("meldvm: revived a node that is not removed");
  alive_[n] = 1;
  --removedNodes_;
  noteLiveNodes();
}

void Database::clearNode(NodeId n) {
  checkNode(n);
  clearScratch();
  for (std::uint32_t t = 0; t < tableCount_; ++t) {
    if (std::as_const(*this).head(n, t).first == kNoFact) continue;  // no page to allocate
    ListHead& h = head(n, t);
    while (h.first != kNoFact) tables_[t].erase(h, h.first);
  }
  for (GroupInputs& g : nodeInputs_) g.clear(n);
}

std::uint32_t Database::requestIndex(PredId p, std::uint32_t field) {
  if (p >= preds_.size()) throw std::out_of_range("meldvm: no predicate " + std::to_string(p));
  FactTable& t = tables_[p];
  for (std::uint32_t x = 0; x < t.indexCount(); ++x)
    if (t.indexKey(x).first == field && t.indexKey(x).count == 1) return x;
  return t.addIndex({field, 1});
}

FactRef Database::addLinear(NodeId n, PredId p, const Value* args, bool adopt) {
  storedPredicate(p, true);
  checkNode(n);
  clearScratch();
  return tables_[p].insert(head(n, p), n, args, 1, kNoFact, adopt);
}

void Database::consume(NodeId n, PredId p, FactRef f) {
  storedPredicate(p, true);
  clearScratch();
  tables_[p].erase(head(n, p), f);
}

void Database::updateLinear(NodeId n, PredId p, FactRef f, const Value* args, bool moveToBack) {
  storedPredicate(p, true);
  clearScratch();
  if (moveToBack) tables_[p].moveToBack(head(n, p), f);
  tables_[p].replaceArgs(head(n, p), f, args);
}

void Database::releaseScratch() {
  if (holdsRemoved_) {
    references_[removedPred_].release(heap_, removed_.data());
    holdsRemoved_ = false;
  }
  if (holdsInput_) {
    references_[inputPred_].release(heap_, input_.data());
    holdsInput_ = false;
  }
  if (!sumList_.isNil()) {
    // Only `sum list float` builds values; its field type is a list of floats.
    heap_.releaseStored(sumList_.asObject()->type, sumList_);
    sumList_ = Value::nil();
  }
}

void Database::keepRemoved(PredId p, FactRef f) {
  setValues(removed_, tables_[p].args(f), preds_[p].arity());
  if (references_[p].empty()) return;
  references_[p].retain(heap_, removed_.data());
  removedPred_ = p;
  holdsRemoved_ = true;
}

FactRef Database::find(NodeId n, PredId p, const Value* args) const {
  const PredicateDesc& d = preds_[p];
  const FactTable& t = tables_[p];
  if (d.persistent() && !d.compact && !d.aggregated()) return t.find(n, args);
  const TypeTable& types = heap_.types();
  for (FactRef f = head(n, p).first; f != kNoFact; f = t.next(f)) {
    bool same = true;
    for (std::uint32_t i = 0; i < d.arity() && same; ++i)
      same = valuesEqual(types, d.fields[i], t.args(f)[i], args[i]);
    if (same) return f;
  }
  return kNoFact;
}

std::uint32_t Database::aggregateInputs(NodeId n, PredId p) const {
  if (groupInputs_[p] != kNoTable) return nodeInputs_[groupInputs_[p]].size(n);
  return inputTable_[p] == kNoTable ? 0 : head(n, inputTable_[p]).size;
}

Change Database::derive(NodeId n, PredId p, const Value* args, std::uint32_t copies) {
  const PredicateDesc& d = storedPredicate(p, false);
  checkNode(n);
  clearScratch();
  if (d.aggregated()) return aggregateChange(n, p, args, copies, true);
  Change c;
  const FactRef f = addCopies(n, p, d, args, copies, c.count);
  if (f == kNoFact) return c;
  setValues(added_, tables_[p].args(f), d.arity());
  c.added = true;
  c.addedArgs = added_;
  return c;
}

FactRef Database::addCopies(NodeId n, PredId p, const PredicateDesc& d, const Value* args,
                            std::uint32_t copies, std::uint32_t& count) {
  FactTable& t = tables_[p];
  if (!d.compact) {  // compact predicates append every derivation (§4.4)
    if (const FactRef f = t.find(n, args); f != kNoFact) {
      t.setCount(f, t.count(f) + copies);
      count = t.count(f);
      return kNoFact;
    }
  }
  count = copies;
  return grouped_[p] ? t.insertGrouped(head(n, p), n, args, copies) : t.insert(head(n, p), n, args, copies);
}

bool Database::deriveEach(NodeId n, PredId p, const Value* args, std::uint32_t count) {
  const PredicateDesc& d = storedPredicate(p, false);
  checkNode(n);
  clearScratch();
  if (d.aggregated()) throw std::logic_error("meldvm: deriveEach on aggregated '" + d.name + "'");
  if (d.compact && !grouped_[p]) {  // compact predicates append every derivation (§4.4)
    tables_[p].appendEach(head(n, p), n, args, count);
    return count != 0;
  }
  bool added = false;
  std::uint32_t copies;
  for (std::uint32_t i = 0; i < count; ++i, args += d.arity())
    added = addCopies(n, p, d, args, 1, copies) != kNoFact || added;
  return added;
}

Change Database::retract(NodeId n, PredId p, const Value* args, std::uint32_t copies) {
  const PredicateDesc& d = storedPredicate(p, false);
  checkNode(n);
  clearScratch();
  if (d.aggregated()) return aggregateChange(n, p, args, copies, false);
  FactTable& t = tables_[p];
  Change c;
  const FactRef f = find(n, p, args);
  if (f == kNoFact) {
    c.found = false;
    return c;
  }
  if (t.count(f) > copies) {
    t.setCount(f, t.count(f) - copies);
    c.count = t.count(f);
    return c;
  }
  keepRemoved(p, f);
  t.erase(head(n, p), f);
  c.removed = true;
  c.removedArgs = removed_;
  return c;
}

}  // namespace meldvm
