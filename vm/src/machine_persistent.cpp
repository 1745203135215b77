// The Machine's persistent facts (§6.5, §6.8): the FIFO of derivations and retractions, and the
// persistent rules (processes) they trigger.
#include "interpreter.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

void Machine::processPersistent() {
  constexpr std::size_t kAhead = 4;
  for (std::size_t i = persistentHead_; i < persistentQueue_.size() && i < persistentHead_ + kAhead - 1; ++i)
    db_->prefetchDerive(persistentQueue_[i].node, persistentQueue_[i].pred,
                        persistentArgs_.data() + persistentQueue_[i].args);
  while (persistentHead_ < persistentQueue_.size()) {
    const PendingFact e = persistentQueue_[persistentHead_++];
    const NodeId n = e.node;  // the running node, or the thread node for thread facts (§6.12)
    // Fetch the hash buckets of an entry a few places ahead: most entries take less time than a
    // memory access.
    if (persistentHead_ + kAhead - 1 < persistentQueue_.size()) {
      const PendingFact& next = persistentQueue_[persistentHead_ + kAhead - 1];
      db_->prefetchDerive(next.node, next.pred, persistentArgs_.data() + next.args);
    }
    // The database copies what it keeps, and nothing appends to the queue before the release.
    const Value* input = persistentArgs_.data() + e.args;
    const Change c = e.negative ? db_->retract(n, e.pred, input) : db_->derive(n, e.pred, input);
    releaseArgs(e.pred, input);  // the queue's references
    if (c.removed) {
      triggerRemoved_.assign(c.removedArgs.begin(), c.removedArgs.end());
      for (std::uint32_t i = 0; i < triggerRemoved_.size(); ++i)
        heap_.retain(program_.predicates[e.pred].fields[i], triggerRemoved_[i]);
      std::vector<Value>& added = triggerAdded_;
      added.clear();
      if (c.added) added.assign(c.addedArgs.begin(), c.addedArgs.end());
      for (std::uint32_t i = 0; i < added.size(); ++i)
        heap_.retain(program_.predicates[e.pred].fields[i], added[i]);
      factRemoved(n, e.pred);
      runProcesses(n, e.pred, triggerRemoved_.data(), true);
      releaseArgs(e.pred, triggerRemoved_.data());
      if (c.added) {
        factAdded(n, e.pred);
        runProcesses(n, e.pred, added.data(), false);
        releaseArgs(e.pred, added.data());
      }
    } else if (c.added) {
      triggerAdded_.assign(c.addedArgs.begin(), c.addedArgs.end());
      for (std::uint32_t i = 0; i < triggerAdded_.size(); ++i)
        heap_.retain(program_.predicates[e.pred].fields[i], triggerAdded_[i]);
      factAdded(n, e.pred);
      runProcesses(n, e.pred, triggerAdded_.data(), false);
      releaseArgs(e.pred, triggerAdded_.data());
    }
  }
  persistentQueue_.clear();
  persistentArgs_.clear();
  persistentHead_ = 0;
}

void Machine::runProcesses(NodeId n, PredId p, const Value* args, bool negative) {
  for (std::uint32_t i : processesOf_[p]) {
    try {
      interp_->run(program_.processes[i].block, n, negative, p, args);
    } catch (const RuntimeError& e) {
      fail(e, n, "persistent rule (" + program_.processes[i].block.label + ")");
    }
    storeDerivedLinear();
  }
}
}  // namespace meldvm
