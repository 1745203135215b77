// The Machine's messages (§6.6): facts for other nodes, posted when a node run ends, and taken
// in when the receiver runs.
#include "mailboxes.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

void Machine::post(NodeId dest, PredId p, const Value* args, bool negative) {
  const PredicateDesc& d = program_.predicates[p];
  if (boxedField_[p])
    for (std::uint32_t i = 0; i < d.arity(); ++i) heap_.retain(d.fields[i], args[i]);
  mail_->post(dest, p, negative, args, d.arity());
  if (!host_ && !(inRun_ && dest == running_)) sched_.wake(dest);
}

void Machine::flushOutgoing() {
  if (host_) {
    for (const auto* list : {&sentPersistent_, &sentLinear_})
      for (const PendingFact& e : *list) {
        const Value* args = sentArgs_.data() + e.args;
        host_->transmit(running_, e.node, e.pred, args, e.negative, e.delayMs);
        releaseArgs(e.pred, args);
      }
  } else {
    postAll(sentPersistent_);
    postAll(sentLinear_);
  }
  sentPersistent_.clear();
  sentLinear_.clear();
  sentArgs_.clear();
}

void Machine::postAll(const std::vector<PendingFact>& facts) {
  constexpr std::size_t kBoxAhead = 8, kTailAhead = 4;  // mailbox entry, then its last chunk
  const std::size_t n = facts.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kBoxAhead < n) {
      mail_->prefetchBox(facts[i + kBoxAhead].node);
      if (!host_) sched_.prefetch(facts[i + kBoxAhead].node);
    }
    if (i + kTailAhead < n) mail_->prefetchTail(facts[i + kTailAhead].node);
    const PendingFact& e = facts[i];
    const Value* args = sentArgs_.data() + e.args;
    post(e.node, e.pred, args, e.negative);
    releaseArgs(e.pred, args);
  }
}

void Machine::deliverIncoming(NodeId n) {
  mail_->drain(n, [&](PredId p, bool negative, const Value* args) {
    if (program_.predicates[p].linear) {
      db_->addLinear(n, p, args);
      releaseArgs(p, args);
      factAdded(n, p);
    } else {  // the mailbox's references pass to the queue
      persistentQueue_.push_back({n, p, negative, std::uint32_t(persistentArgs_.size())});
      persistentArgs_.insert(persistentArgs_.end(), args, args + program_.predicates[p].arity());
    }
  });
}
}  // namespace meldvm
