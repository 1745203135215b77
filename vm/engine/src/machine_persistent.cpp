// The Machine's persistent facts (§6.5, §6.8): the FIFO of derivations and retractions, and the
// persistent rules (processes) they trigger.
#include "interpreter.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

void Machine::processQueuedPersistent() {
  constexpr std::size_t kAhead = 4;
  for (std::size_t i = persistentHead_; i < persistentQueue_.size() && i < persistentHead_ + kAhead - 1; ++i)
    db_->prefetchDerive(persistentQueue_[i].node, persistentQueue_[i].pred,
                        persistentArgs_.data() + persistentQueue_[i].args);
  while (persistentHead_ < persistentQueue_.size()) {
    const PendingFact e = persistentQueue_[persistentHead_++];
    if (e.cancelled) continue;
    if (e.negative) {
      --queuedRetractions_;
    } else if (queuedRetractions_ != 0 && cancelledByLaterRetraction(e)) {
      releaseArgs(e.pred, persistentArgs_.data() + e.args);
      continue;
    }
    const NodeId n = e.node;  // the running node, or the thread node for thread facts (§6.12)
    // Fetch the hash buckets of an entry a few places ahead: most entries take less time than a
    // memory access.
    if (persistentHead_ + kAhead - 1 < persistentQueue_.size()) {
      const PendingFact& next = persistentQueue_[persistentHead_ + kAhead - 1];
      db_->prefetchDerive(next.node, next.pred, persistentArgs_.data() + next.args);
    }
    // The database copies what it keeps, and nothing appends to the queue before the release.
    applyPersistent(n, e.pred, persistentArgs_.data() + e.args, e.negative);
  }
  persistentQueue_.clear();
  persistentArgs_.clear();
  persistentHead_ = 0;
}

// The established VM's rule (§6.8): a derivation whose retraction already waits later in the queue
// runs neither; both are dropped. An aggregate that moves through several values while its inputs
// arrive leaves such pairs behind for the facts derived from its passing values: dropping them
// keeps those values from cascading through the rules downstream (a three-layer neural network
// trained this way derived without bound; issue 10, point 11).
bool Machine::cancelledByLaterRetraction(const PendingFact& e) {
  const PredicateDesc& d = program_.predicates[e.pred];
  const Value* args = persistentArgs_.data() + e.args;
  for (std::size_t i = persistentHead_; i < persistentQueue_.size(); ++i) {
    PendingFact& q = persistentQueue_[i];
    if (!q.negative || q.cancelled || q.pred != e.pred || q.node != e.node) continue;
    const Value* other = persistentArgs_.data() + q.args;
    bool same = true;
    for (std::size_t k = 0; k < d.fields.size() && same; ++k)
      same = valuesEqualFast(program_.types, d.fields[k], args[k], other[k]);
    if (!same) continue;
    q.cancelled = true;
    --queuedRetractions_;
    releaseArgs(q.pred, other);
    return true;
  }
  return false;
}

// A persistent derivation or retraction changed what is visible at node n (§6.5, §6.8): run the
// processes of the fact that disappeared (negative mode), then of the one that appeared.
void Machine::publishChange(NodeId n, PredId p, const Change& c) {
  // Own copies: the processes change the store, whose scratch the Change points into.
  triggerRemoved_.assign(c.removedArgs.begin(), c.removedArgs.end());
  triggerAdded_.assign(c.addedArgs.begin(), c.addedArgs.end());
  if (db_->holdsReferences(p)) {
    if (c.removed) retainArgs(p, triggerRemoved_.data());
    if (c.added) retainArgs(p, triggerAdded_.data());
  }
  // On robots the facts these processes send travel over links with delays, and a neighbour acts
  // on each as it arrives: an aggregate that moves from one value to another announces the new
  // value before retracting the old one, so that a neighbour whose own aggregate rests on the old
  // value moves once, to the new one, instead of falling back and cascading the fall through the
  // ensemble before the new value catches up (issue 10, point 15). On its own graph the VM keeps
  // the established order: retraction first.
  const bool addFirst = host_ != nullptr && c.removed && c.added;
  if (addFirst) publishAdded(n, p);
  if (c.removed) {
    factRemoved(n, p);
    runProcesses(n, p, triggerRemoved_.data(), true);
    releaseArgs(p, triggerRemoved_.data());
  }
  if (c.added && !addFirst) publishAdded(n, p);
}

void Machine::publishAdded(NodeId n, PredId p) {
  factAdded(n, p);
  runProcesses(n, p, triggerAdded_.data(), false);
  releaseArgs(p, triggerAdded_.data());
}

void Machine::runProcesses(NodeId n, PredId p, const Value* args, bool negative) {
  // §6.12: a new thread fact, while a node runs, triggers the persistent rules that also read
  // node facts at that node (the established VM runs them with the running node as host).
  const bool atRunningNode = n == threadNode_ && inRun_ && running_ != threadNode_;
  for (std::uint32_t i : tables_.processesOf[p]) {
    const NodeId host = atRunningNode && !tables_.processNeeds[i].empty() ? running_ : n;
    bool ready = true;  // a loop over a predicate without facts here: nothing can fire
    for (PredId q : tables_.processNeeds[i]) ready = ready && db_->factCount(host, q) != 0;
    if (!ready) continue;
    countStep();
    try {
      interp_->run(program_.processes[i].block, host, negative, p, args);
    } catch (const RuntimeError& e) {
      fail(e, host, "persistent rule (" + program_.processes[i].block.label + ")");
    }
    storeDerivedLinear();
  }
}
}  // namespace meldvm
