// The nodes `exists` creates: their deletion during the run, as the established VM deletes them
// (node_recycling.hpp), and the collection of those left when the run ends (§6.10).
#include "meldvm/machine.hpp"
#include "meldvm/mailboxes.hpp"

namespace meldvm {

void Machine::freeDroppedNodes() {
  // The established VM keeps these candidates in a hash set keyed by node address, which it
  // walks (for a few nodes, in distinct buckets) the last inserted first.
  NodeReferences& refs = recycling_.refs();
  for (std::size_t i = refs.dropped().size(); i-- > 0;) {
    const NodeId n = refs.dropped()[i];
    if (n != running_ && unusedCreatedNode(n)) deleteCreatedNode(n);
  }
  refs.clearDropped();
}

bool Machine::unusedCreatedNode(NodeId n) const {
  if (n >= created_.size() || !created_[n] || !db_->alive(n) || recycling_.refs().count(n) != 0) return false;
  if (!mail_->empty(n) || sched_.waiting(n)) return false;
  for (PredId p = 0; p < program_.predicates.size(); ++p)
    if (db_->factCount(n, p) != 0) return false;
  return true;
}

void Machine::deleteCreatedNode(NodeId n) {
  db_->removeNode(n);
  std::fill_n(candidates_.data() + std::size_t(n) * tables_.ruleWords, tables_.ruleWords, 0);
  recycling_.freed(n);
}

// ---- end of the run ----

void Machine::collectGarbageNodes() {
  // §6.10: a created node with no facts that no fact refers to is deleted.
  const std::vector<NodeId> empty = emptyCreatedNodes();
  if (empty.empty()) return;
  std::vector<std::uint8_t> referenced;
  markReferencedNodes(referenced);
  for (NodeId n : empty)
    if (n >= referenced.size() || !referenced[n]) db_->removeNode(n);
}

std::vector<NodeId> Machine::emptyCreatedNodes() const {
  std::vector<NodeId> empty;
  for (NodeId n = initialNodes_; n < db_->nodeCount(); ++n) {
    if (!created_[n] || !db_->alive(n)) continue;
    bool hasFacts = false;
    for (PredId p = 0; p < program_.predicates.size() && !hasFacts; ++p) hasFacts = db_->factCount(n, p) != 0;
    if (!hasFacts) empty.push_back(n);
  }
  return empty;
}

void Machine::markReferencedNodes(std::vector<std::uint8_t>& referenced) const {
  auto mark = [&](NodeId r) {
    if (r >= referenced.size()) referenced.resize(std::size_t(r) + 1, 0);
    referenced[r] = 1;
  };
  for (NodeId n = 0; n < db_->nodeCount(); ++n) {
    if (!db_->alive(n)) continue;
    for (PredId p = 0; p < program_.predicates.size(); ++p) {
      const PredicateDesc& d = program_.predicates[p];
      for (FactRef f = db_->first(n, p); f != kNoFact; f = db_->next(p, f)) {
        const Value* a = db_->args(p, f);
        for (std::uint32_t i = 0; i < d.arity(); ++i) {
          const TypeId t = d.fields[i];
          if (program_.types.kind(t) == TypeKind::Node) {
            mark(a[i].asNode());
          } else if (program_.types.kind(t) == TypeKind::List &&
                     program_.types.kind(program_.types.element(t)) == TypeKind::Node) {
            for (Value l = a[i]; !l.isNil(); l = listTail(l)) mark(listHead(l).asNode());
          }
        }
      }
    }
  }
}

}  // namespace meldvm
