// The Machine's messages (§6.6): facts for other nodes, posted when a node run ends, and taken
// in when the receiver runs.
#include "meldvm/machine.hpp"
#include "meldvm/mailboxes.hpp"
#include "send_order.hpp"

namespace meldvm {

void Machine::post(NodeId dest, PredId p, const Value* args, bool negative, bool adopt) {
  if (!adopt) retainArgsInline(p, args);
  linearPosted_ |= tables_.isLinear[p];
  mail_->post(dest, p, negative, args);
  // The thread node is served apart (runNext), never from the queue.
  if (!host_ && !(nodeRunning_ && dest == running_) && dest != threadNode_) sched_.wake(dest);
}

void Machine::postOrRoute(const PendingFact& e, const Value* args) {
  if (shard_) [[unlikely]] {
    if (const ThreadId owner = ownerOf(e.node); owner != placement_.self) {
      shard_->sendRemote(owner, e.node, e.pred, args, e.negative);  // takes the buffer's references
      return;
    }
  }
  post(e.node, e.pred, args, e.negative, /*adopt=*/true);  // the buffer's references go to the mailbox
}

void Machine::flushOutgoing() {
  if (host_) {
    for (const std::span<const PendingFact> list : {sentPersistent_.items(), sentLinear_.items()})
      for (const PendingFact& e : list) {
        const Value* args = sentArgs_.data() + e.args;
        host_->transmit(running_, e.node, e.pred, args, e.negative, e.delayMs);
        releaseArgs(e.pred, args);
      }
  } else {
    postAll(sentPersistent_.items(), nullptr);
    // The linear ones in the established VM's delivery order (send_order.hpp).
    const std::vector<std::uint32_t>* order = sendOrder_->arrange(
        sentLinear_.size(), [&](std::size_t i) { return sentLinear_[i].node; },
        [&](std::size_t i) { return sentLinear_[i].pred; });
    if (order)
      storeSentLinear([&](std::size_t i) -> const PendingFact& { return sentLinear_[(*order)[i]]; });
    else
      storeSentLinear([&](std::size_t i) -> const PendingFact& { return sentLinear_[i]; });
  }
  sentPersistent_.clear();
  sentLinear_.clear();
  sentArgs_.clear();
}

void Machine::postAll(std::span<const PendingFact> facts, const std::vector<std::uint32_t>* order) {
  // Each destination's mailbox entry and scheduler record are fetched a few posts ahead, then,
  // fewer posts ahead, the last chunk of its mailbox, whose address is only known from the entry
  // (the first ones before the loop). (send() fetched the entries of the facts the VM sent when
  // they were derived; native code's persistent facts come without: shortest-path's posts then
  // waited for the entries, a fifth of its native run.)
  constexpr std::size_t kEntryAhead = 8, kTailAhead = 4;
  const std::size_t n = facts.size();
  // (A shard's facts may name nodes of other threads beyond its own arrays: no prefetch there.)
  const NodeId nodes = db_->nodeCount();
  auto at = [&](std::size_t i) -> const PendingFact& { return facts[order ? (*order)[i] : i]; };
  for (std::size_t i = 0; i < n && i < kEntryAhead; ++i)
    if (at(i).node < nodes) prefetchMailEntry(at(i).node);
  for (std::size_t i = 0; i < n && i < kTailAhead; ++i)
    if (at(i).node < nodes) mail_->prefetchTail(at(i).node);
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kEntryAhead < n && at(i + kEntryAhead).node < nodes) prefetchMailEntry(at(i + kEntryAhead).node);
    if (i + kTailAhead < n && at(i + kTailAhead).node < nodes) mail_->prefetchTail(at(i + kTailAhead).node);
    const PendingFact& e = at(i);
    postOrRoute(e, sentArgs_.data() + e.args);  // takes the buffer's references
  }
}

inline bool Machine::storedOnArrival(const PendingFact& e) const {
  return ownerOf(e.node) == placement_.self && mail_->empty(e.node) &&
         db_->listHeads(e.node)[e.pred].size < kStoredOnArrivalBelow;
}

// One machine on its own graph stores the linear facts a run sent straight into their receivers,
// as the established VM stores them on arrival (no mailbox: a copy and a pass less per fact). The
// order is the one a mailbox would give: nothing else adds facts to a node before its next run,
// and a node that sent itself facts runs again (runNode). The thread node's facts are visible to
// every node's rules: they wait in its mailbox until it runs.
// A threaded run's shard stores them so only for a node it owns whose mailbox is empty (so the
// arrival order stays the mailbox's) and whose list of that predicate is short
// (kStoredOnArrivalBelow); the others go to mailboxes, where a node takes its messages in slices
// and moves to another thread with them as a chain of chunks. (Everything stored on arrival,
// 8queens-12 at -j 2 took 3.3-3.6 s and 53-83 MB instead of 2.2-2.4 s and 35-39 MB: its nodes
// pile up tens of thousands of placements. Everything through mailboxes, the post and the
// delivery were a sixth of heat-transfer's run at -j 2, where a node holds a few facts.)
// at(i): the i-th fact in delivery order. Each receiver's list heads are looked up once, for the
// fact and for the rules it wakes; storing linear facts takes no scratch value, so what the store
// held from before is released once.
template <class At>
void Machine::storeSentLinear(At at) {
  constexpr std::size_t kTailAhead = 4;  // send() fetched the list heads: now their last facts
  const std::size_t n = sentLinear_.size();
  // (A shard's facts may name nodes of other threads beyond its own arrays: no prefetch there.)
  const NodeId nodes = db_->nodeCount();
  auto prefetch = [&](const PendingFact& e) {
    if (!shard_ || e.node < nodes) db_->prefetchListTail(e.node, e.pred);
  };
  db_->releaseHeldScratch();
  for (std::size_t i = 0; i < n && i < kTailAhead; ++i) prefetch(at(i));
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kTailAhead < n) prefetch(at(i + kTailAhead));
    const PendingFact& e = at(i);
    const Value* args = sentArgs_.data() + e.args;
    if (e.node == threadNode_) [[unlikely]] {
      post(e.node, e.pred, args, false, /*adopt=*/true);
      continue;
    }
    if (shard_ && !storedOnArrival(e)) {
      postOrRoute(e, args);  // takes the buffer's references
      continue;
    }
    ListHead* heads = db_->listHeadsForWrite(e.node);
    db_->addLinearTrustedAt(heads, e.node, e.pred, args);  // the buffer's references go to the fact
    factAdded(e.node, e.pred, heads);
    if (nodeRunning_ && e.node == running_)
      sentItself_ = true;
    else
      sched_.wake(e.node);
  }
}

void Machine::deliverIncoming(NodeId n) {
  // Linear facts join the store first, in arrival order; then the persistent ones are processed in
  // arrival order, straight from the mailbox (what they derive locally queues behind them, as in
  // one FIFO, §6.5). Nothing posts to the running node, so the box is stable meanwhile. Until a
  // linear fact has been sent at all, the first pass has nothing to find.
  bool persistent = !linearPosted_;
  delivering_ = true;
  // A shard's node may take in tens of thousands of facts at once (8queens-12): a rebalance would
  // wait for all of them to be stored, so the runtime gets a safe point every few hundred. Facts
  // it takes in for this node meanwhile are held back (receive), other nodes' boxes are not this
  // one's, and this node does not move.
  std::uint32_t untilSafePoint = kFactsBetweenSafePoints;
  const std::uint32_t chunks = shard_ ? kChunksPerShardDelivery : Mailboxes::kAllChunks;
  if (linearPosted_)
    mail_->forEach(
        n,
        [&](PredId p) {
          persistent = persistent || !tables_.isLinear[p];
          return tables_.isLinear[p] != 0;
        },
        [&](PredId p, bool, const Value* args) {
          db_->addLinearTrusted(n, p, args);  // the mailbox's references go to the fact
          factAdded(n, p);
          if (safePointFlag_ && --untilSafePoint == 0) [[unlikely]] {
            untilSafePoint = kFactsBetweenSafePoints;
            if (safePointFlag_->load(std::memory_order_relaxed)) shard_->safePoint();
          }
        },
        chunks);
  if (persistent)
    mail_->forEach(
        n, [&](PredId p) { return tables_.isLinear[p] == 0; },
        [&](PredId p, bool negative, const Value* args) { applyPersistent(n, p, args, negative); }, chunks);
  mail_->release(n, chunks);
  delivering_ = false;
  if (!heldBack_.empty()) [[unlikely]] {
    for (const PendingFact& e : heldBack_) {
      const Value* args = heldBackArgs_.data() + e.args;
      post(e.node, e.pred, args, e.negative);
      releaseArgs(e.pred, args);
    }
    heldBack_.clear();
    heldBackArgs_.clear();
  }
}
}  // namespace meldvm
