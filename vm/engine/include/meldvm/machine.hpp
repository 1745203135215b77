// The Meld virtual machine on its own graph (the `meld` command): one Program, its nodes, their
// databases, the rule engine of spec §6.4–6.10 and the serial scheduler of §6.11.
//
// A node run (§6.4.6): deliver the facts that arrived for the node, run the persistent processes
// they trigger (§6.5), then repeatedly run the lowest-numbered candidate rule (§6.4.2); after each
// rule run the consumed facts are unlinked, the derived linear facts appended (§6.4.4) and the
// queued persistent facts processed. Linear facts for other nodes are delivered when the node run
// ends; persistent ones at once.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <memory_resource>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "meldvm/builtins.hpp"
#include "meldvm/consumed_facts.hpp"
#include "meldvm/database.hpp"
#include "meldvm/heap.hpp"
#include "meldvm/large_allocator.hpp"
#include "meldvm/mailboxes.hpp"
#include "meldvm/native_array.hpp"
#include "meldvm/node_recycling.hpp"
#include "meldvm/program.hpp"
#include "meldvm/program_tables.hpp"
#include "meldvm/serial_scheduler.hpp"
#include "meldvm/shard.hpp"
#include "meldvm/value_buffer.hpp"

namespace meldvm {

// What a Machine asks of the code that drives it from outside (the robot runtime, where every
// node is a simulated block): the facts that leave a node and the actions it takes. Without a
// host, a Machine runs its own graph: facts go to local mailboxes, write-string prints.
class MachineHost {
 public:
  virtual ~MachineHost() = default;
  // A fact derived at `from` for node `to` (another node, or `from` itself with a delay), handed
  // over when the node run ends (§6.4.4); `delayMs` from a `@+N` head. Arguments are borrowed.
  virtual void transmit(NodeId from, NodeId to, PredId p, const Value* args, bool negative,
                        std::uint32_t delayMs) = 0;
  // An action fact (§7.2) derived at `from` for node `to`; never stored.
  virtual void action(NodeId from, NodeId to, PredId p, const Value* args) = 0;
  // Whether node `from` can send a fact to node `to` (robots: only to a neighbour). Asked when the
  // rule derives the fact, so that an error names the rule.
  virtual bool reachable(NodeId from, NodeId to) = 0;
};

class NativeCode;

struct MachineOptions {
  std::vector<std::string> args;   // @arg1.. (program arguments after `--`)
  std::ostream* output = nullptr;  // write-string output (nullptr: discarded)
  MachineHost* host = nullptr;     // set: the nodes are driven from outside (receive, runNode)
  NodeId nodes = 0;                // at least this many nodes (with a host: one per block)
  std::uint64_t seed = 0;          // the random stream of randint & co. (meld --seed)
  // Steps allowed before the run stops with a RuntimeError (0: no limit): a step is a rule run, a
  // persistent-process run, a loop run (an inner loop runs once per fact of the loops around it),
  // a linear fact stored for the node that derived it, or a node created. Bounds what a program (or a damaged
  // bytecode file) can make the VM do.
  std::uint64_t maxSteps = 0;
  // Set: this Machine is one shard of a threaded run (shard.hpp, vm/threads) and owns only the
  // nodes of `placement`; facts for other nodes go through the link.
  ShardLink* shard = nullptr;
  ShardPlacement placement;
  // Required with `shard`: the chunk table that the mailboxes of every shard of the run share, so
  // that a moving node's waiting messages change shards as they are (mail_slabs.hpp). It must
  // outlive every shard.
  MailSlabs* mailSlabs = nullptr;
  // Set by another thread to end the run (stop-program elsewhere, an error): read between rule
  // runs, so that a node run that would never end on its own still stops.
  const std::atomic<bool>* stopFlag = nullptr;
  // Set by the threaded runtime when it wants every thread at a safe point (a rebalance): read
  // between rule runs and every few hundred facts a node run takes in, where the machine then
  // calls shard->safePoint().
  const std::atomic<bool>* safePointFlag = nullptr;
  // Native entry points of the program's blocks (meld --jit, a native .so); they must outlive the
  // machine. nullptr: everything runs in the interpreter.
  const NativeCode* native = nullptr;
  // false: the coordination instructions that steer the order of work (set-priority,
  // add-priority, remove-priority, set-default-priority, set-static, set-moving, set-cpu,
  // set-affinity) and stop-program do nothing, as under the established VM's -n (meld
  // --no-scheduling); schedule-next still works there too.
  bool coordination = true;
};

// Memory a machine holds for its nodes, by part (capacities, not what is in use).
struct MemoryUse {
  std::size_t factTables = 0;  // fact slots, their hash tables, aggregate inputs
  std::size_t listHeads = 0;   // per-node list heads and liveness marks
  std::size_t heaps = 0;       // boxed values (lists, strings, ...)
  std::size_t mailboxes = 0;   // pending facts and per-node boxes
  std::size_t scheduling = 0;  // scheduler records, candidate sets, created-node marks
  // What a node run works in (facts consumed, derived and sent, queued persistent facts) and, with
  // threads, the batches between them: kept at the size of the largest run.
  std::size_t buffers = 0;
  std::size_t total() const { return factTables + listHeads + heaps + mailboxes + scheduling + buffers; }
  MemoryUse& operator+=(const MemoryUse& o) {
    factTables += o.factTables;
    listHeads += o.listHeads;
    heaps += o.heaps;
    mailboxes += o.mailboxes;
    scheduling += o.scheduling;
    buffers += o.buffers;
    return *this;
  }
};

struct MachineStats {
  std::uint64_t factsDerived = 0;   // facts derived by heads (linear and persistent, sent ones included)
  std::uint64_t factsConsumed = 0;  // linear facts consumed
  std::uint64_t factsSent = 0;      // facts sent to another node
  std::uint64_t rulesFired = 0;     // rule firings (a comprehension's matches not counted)
  // Facts the rules' loops looked at, whether they matched or not: the work of rules that do not
  // fire (the multicore target's chip charges it).
  std::uint64_t factsTried = 0;
  std::uint64_t nodeRuns = 0;
};

class DerivationLog;
class Interpreter;
namespace detail {
class SendOrder;
}

class Machine : private SchedulerView {
 public:
  Machine(const Program& program, MachineOptions options = {});
  ~Machine() override;
  // Drops every reference the machine holds (its facts, messages, globals): the end of the
  // machine but for its heap. Shards that handed values to each other all do this before any of
  // their heaps goes (threads/README.md).
  void releaseAll();
  Machine(const Machine&) = delete;
  Machine& operator=(const Machine&) = delete;

  // Creates the nodes (one `_init` fact each) and computes the constants; run() starts with it.
  void start();
  // Runs to global quiescence or stop-program. Throws RuntimeError naming the rule and node.
  void run();
  // One node run: the next node of the scheduler (§6.11), else the thread node if it has work.
  // False when nothing is left to run here (a shard then waits for facts from other threads).
  bool runNext();

  // Driving the nodes from outside (MachineOptions::host): a fact arrives at node n (a message, a
  // sensor change; negative = a retraction), and node n runs until it has nothing left to do.
  // runNode returns the number of rules fired. Both throw RuntimeError like run().
  // adopt: the machine takes over the references of the boxed arguments (else it takes its own).
  // Throws, having taken nothing, for a node it does not hold.
  void receive(NodeId n, PredId p, const Value* args, bool negative, bool adopt = false);
  std::uint64_t runNode(NodeId n);
  bool hasWork(NodeId n) const;
  // A node for a block that joined the world after the start (the host drives it like the others):
  // it gets its `_init` fact, and rule 0's axioms of variable home; the axioms written for a
  // node literal belong to the initial nodes. Returns its id (the next one).
  NodeId addHostNode();
  // Room for that many facts of p (all nodes together), when the driver knows the count.
  void reserveFacts(PredId p, std::size_t facts) { db_->reserve(p, facts); }
  bool stopped() const { return stop_; }
  bool stopRequested() const { return stop_ || interrupted(); }
  // Stopped from outside (another thread's stop-program, a cancel): the run in progress ends at
  // once, where this machine's own stop-program lets it finish (§6.13).
  // (stopFlag_ is never null: a machine alone points it at noStop_, so the common case is one
  // load and test, asked for every fact a loop visits.)
  bool interrupted() const { return stopFlag_->load(std::memory_order_relaxed) && !stop_; }
  // Another thread ran stop-program: stop after the current node run.
  void requestStop() { stop_ = true; }
  // A coordination fact (§5.7) that another thread sent for a node of this shard.
  void coordinateOwned(Opcode op, NodeId n, double value);
  const ShardPlacement& placement() const { return placement_; }
  std::size_t waitingNodes() const { return sched_.waiting(); }  // queued for a run
  // The garbage collection of created nodes (§6.10) in pieces, for a threaded run whose nodes
  // refer to each other across shards: the created nodes here with no fact, the nodes the facts
  // here refer to (`referenced` grows as needed), and the removal.
  std::vector<NodeId> emptyCreatedNodes() const;
  void markReferencedNodes(std::vector<std::uint8_t>& referenced) const;
  void removeNode(NodeId n) { db_->removeNode(n); }
  // Hints for a fact about to be posted to node n from outside a node run (a thread's batch,
  // ShardMail::apply): its mailbox entry and scheduler record, then, once the entry has arrived,
  // the end of its mailbox. (Always inlined: GCC drops calls to functions whose only effect is a
  // prefetch.)
  [[gnu::always_inline]] void prefetchPost(NodeId n) const {
    if (n < db_->nodeCount()) prefetchMailEntry(n);
  }
  [[gnu::always_inline]] void prefetchPostTail(NodeId n) const {
    if (n < db_->nodeCount()) mail_->prefetchTail(n);
  }
  // What a post to node n (< nodeCount) touches first: its mailbox entry and scheduler record.
  [[gnu::always_inline]] void prefetchMailEntry(NodeId n) const {
    mail_->prefetchBox(n);
    sched_.prefetch(n);
  }
  // What storing a linear fact sent to node n touches besides its list (storeSentLinear): its
  // scheduler record and the candidate rules it marks, fetched when the fact is sent (the
  // candidates' word waited for memory in a fifth of the stores).
  [[gnu::always_inline]] void prefetchStoreTarget(NodeId n) const {
    sched_.prefetch(n);
    __builtin_prefetch(candidates_.data() + std::size_t(n) * tables_.ruleWords, 1);
  }
  // Whether the node's facts are here: a live node of the graph or thread node, or a node created
  // here (a shard's arrays also span the other threads' nodes and unused created ids).
  bool holdsNode(NodeId n) const {
    if (n >= db_->nodeCount() || !db_->alive(n)) return false;
    return n < initialNodes_ + (threadNode_ != kNoNode ? placement_.threads : 0) || created_[n];
  }
  // The heap of this Machine's values (facts from other threads are rebuilt in it).
  Heap& heap() { return heap_; }

  // Work stealing: nodes move between the shards of a threaded run, between node runs or at a
  // safe point of one (ShardLink::safePoint), where every node may move but the running one. The
  // thread giving nodes away picks `max` of its queued nodes and the idle ones among them, a band
  // of its ids at the end that faces the taker (highestIds: the taker's range lies above this
  // shard's); graph nodes only, not static ones. It hands over each one's scheduling state, facts
  // and waiting messages and forgets it; the taker adopts the state (takeNode), stores the facts,
  // posts the messages, and queues the node if it has work.
  std::vector<NodeId> pickNodesToGive(std::size_t max, bool highestIds);
  // A node set-cpu sends to another thread: out of the queue, to be given away (false: it is
  // no longer here, not a node of the graph, or running now).
  bool unqueueToGive(NodeId n);
  bool movableNow(NodeId n) const { return !(nodeRunning_ && n == running_); }
  // The taker's side of set-cpu: the node is pinned and just-moved is added (§5.7).
  void settleMovedNode(NodeId n);
  // `stored` sees each stored fact (the store keeps and then releases its references); `waiting`
  // each waiting message, whose references stay with it: the messages leave in
  // `GivenNode::waiting`, chunks and all, for the taker's takeNode (the shards share MailSlabs).
  using StoredFactVisitor = std::function<void(PredId, const Value*, std::uint32_t copies)>;
  using WaitingFactVisitor = std::function<void(PredId, const Value*)>;
  struct GivenNode {
    SerialScheduler::Carried state;
    Mailboxes::Chain waiting;
  };
  GivenNode giveNode(NodeId n, const StoredFactVisitor& stored, const WaitingFactVisitor& waiting);
  // After giving nodes away, between node runs: the memory of fact slots they left free
  // (FactTable::releaseFreePages); the bytes given back.
  std::size_t releaseFreePages() { return db_->releaseFreePages(); }
  void takeNode(NodeId n, const SerialScheduler::Carried& state, const Mailboxes::Chain& waiting);
  // The taker's side of a move: takes over the references of the boxed arguments (true) or takes
  // its own (false: the caller keeps its references).
  bool takeStoredFact(NodeId n, PredId p, const Value* args, std::uint32_t copies);
  void takeNodeDone(NodeId n);
  // The store's index on field `field` of `p` (requested at construction for every `index`
  // directive and every ITER_KEY of the program).
  std::uint32_t keyIndex(PredId p, std::uint32_t field) const {
    for (const auto& [f, handle] : keyIndexes_[p])
      if (f == field) return handle;
    return ~0u;
  }
  // Whether the program draws random numbers (on a robot its stream is the block's own).
  bool usesRandom() const { return tables_.usesRandom; }
  // Restarts the random stream from `seed` (a robot does so from its block's stream before a run).
  void reseed(std::uint64_t seed) { rng_.state = seed; }

  void dump(std::ostream& out) const;
  std::string dump() const;

  const MachineStats& stats() const { return stats_; }
  // From now on, notes in `log` where each derived or sent fact comes from (nullptr: stop). The
  // log must outlive the machine or the next call.
  void recordDerivations(DerivationLog* log) { derivations_ = log; }
  DerivationLog* derivations() const { return derivations_; }
  const Database& database() const { return *db_; }
  const Program& program() const { return program_; }
  // Memory the VM holds for its nodes: fact store, values, mailboxes, scheduler, candidate sets.
  std::size_t bytesInUse() const { return memoryUse().total(); }
  MemoryUse memoryUse() const;

 private:
  friend class Interpreter;
  friend struct NativeHelpers;  // the interpreter's helpers for native code (interpreter.cpp)

  // ---- what the interpreter calls ----
  void derive(NodeId host, PredId p, const Value* args, bool negative);
  // derive(host, p, fact, false) for `count` facts stored back to back in `args` (AXIOM_FACTS).
  void deriveEach(NodeId host, PredId p, const Value* args, std::uint32_t count);
  // The common case inline: a linear fact sent by a run of the VM on its own graph and one thread,
  // which waits in a buffer for the run's end (storeSentLinear); every other case in sendAny.
  // (A shard's own nodes' case inline too cost B2 pagerank and n-queens 3-6 % at -j 2: the
  // interpreter's loop, where it lands, is sensitive to what GCC inlines into it.)
  void send(NodeId host, NodeId dest, PredId p, const Value* args, bool negative, std::uint32_t delayMs = 0) {
    if (ownGraphSerial_ && tables_.plainLinear[p] && !negative && dest < db_->nodeCount() && db_->alive(dest))
      return bufferSentLinear(dest, p, args);
    sendAny(host, dest, p, args, negative, delayMs);
  }
  // A linear fact for a live node of this thread, into the buffer that storeSentLinear empties
  // when the run ends; what storing it touches is fetched now.
  [[gnu::always_inline]] void bufferSentLinear(NodeId dest, PredId p, const Value* args) {
    db_->prefetchListHead(dest, p);
    prefetchStoreTarget(dest);
    ++stats_.factsDerived;
    ++runDerived_;
    ++stats_.factsSent;
    sentLinear_.push_back({dest, p, false, std::uint32_t(sentArgs_.size())});
    pushArgs(sentArgs_, p, args);
  }
  void sendAny(NodeId host, NodeId dest, PredId p, const Value* args, bool negative, std::uint32_t delayMs);
  void action(NodeId from, NodeId dest, PredId p, const Value* args);
  // A rule consumed the fact: marked now, unlinked when the rule run ends (finishRuleRun).
  void consumed(NodeId host, PredId p, FactRef f) {
    db_->markConsumed(p, f);
    consumed_.push(host, p, f);
    ++stats_.factsConsumed;
    ++runConsumed_;
  }
  void updated(NodeId host, PredId p, FactRef f, const Value* args, bool moveToBack);
  NodeId newNode();
  NodeId appendNode(bool created);
  void priorityRequest(NodeId n, double p);
  void coordination(Opcode op, NodeId n, Value arg);
  void placeNode(Opcode op, NodeId n, Value arg);  // set-cpu, set-affinity
  void setStatic(NodeId n, bool isStatic);
  bool ownedHere(NodeId n) const { return !shard_ || ownerOf(n) == placement_.self; }
  ThreadId ownerOf(NodeId n) const {
    if (graphOwners_ && n < graphOwners_->size()) return graphOwners_->owner(n);
    return shard_ ? shard_->ownerOf(n) : 0;
  }
  void growNodes(NodeId end);  // node arrays up to id end (a shard's block of created ids)
  void initNode(NodeId n);     // its _init fact
  void stopProgram() {
    if (!options_.coordination) return;
    stop_ = true;
    if (shard_) shard_->stopAll();
  }
  Value programArg(std::uint32_t k) const;

  // ---- node runs ----
  void runRule(NodeId n, std::uint32_t rule);
  void finishRuleRun();
  std::uint32_t takeCandidate(NodeId n, std::uint64_t* cand, bool withThread);
  void unlinkConsumed();  // the facts the rule run consumed leave the store
  static constexpr std::size_t kConsumedInline = 8;
  [[gnu::always_inline]] void unlinkOne(const ConsumedFacts::Fact& c) {
    db_->consumeTrusted(c.node, c.pred, c.fact);
    factRemoved(c.node, c.pred);
  }
  void fetchListsOfConsumed(std::size_t i) const;  // unlinkConsumed, before consuming consumed_[i]
  void publishAdded(NodeId n, PredId p);
  void runOnce(NodeId n);  // one run of node n (runNode repeats it while the node sent itself facts)
  void markThreadCandidates(NodeId n);  // §6.12: at the start of a normal node's run
  void storeUndeliveredLinear();        // after stop-program (§6.13)
  void storeDerivedLinear();            // the linear facts derived for the host, appended in order (§6.4.4)
  void deliverIncoming(NodeId n);
  // The queue's entries name their own nodes. Inline when the queue is empty: it is after most
  // rule runs of a linear program (heat-transfer: 157 K calls, 32 instructions each, for nothing).
  void processPersistent() {
    if (!persistentQueue_.empty()) processQueuedPersistent();
  }
  void processQueuedPersistent();
  // Inline: most derivations change nothing visible (a copy more, an aggregate input that does not
  // win), and then this is all there is to do.
  void applyPersistent(NodeId n, PredId p, const Value* args, bool negative) {
    const Change c = db_->changePersistent(n, p, args, !negative);
    if (db_->holdsReferences(p)) releaseArgs(p, args);  // the references of the queue entry or message
    if (c.removed || c.added) publishChange(n, p, c);
  }
  // Runs the processes of the visible fact that disappeared (negative mode) and of the one that
  // appeared.
  [[gnu::noinline]] void publishChange(NodeId n, PredId p, const Change& c);
  void runProcesses(NodeId n, PredId p, const Value* args, bool negative);
  void flushOutgoing();
  template <class At>
  void storeSentLinear(At at);
  void applyPriorityRequests();
  // Candidate rules (§6.4.2). A rule that is a candidate already needs no look at its other
  // predicates (most adds). Inline: called for every fact stored.
  void factAdded(NodeId n, PredId p) { factAdded(n, p, db_->listHeads(n)); }
  void factAdded(NodeId n, PredId p, const ListHead* heads) {  // heads: the node's list heads
    std::uint64_t* cand = candidates_.data() + std::size_t(n) * tables_.ruleWords;
    const std::uint64_t bits = tables_.triggerBits[p];
    if (tables_.ruleWords != 1 || (cand[0] & bits) != bits) {
      const ProgramTables::RuleTrigger* t = tables_.triggers.data() + tables_.triggersFrom[p];
      const ProgramTables::RuleTrigger* const end = tables_.triggers.data() + tables_.triggersFrom[p + 1];
      for (; t != end; ++t)
        if (!(cand[t->word] & t->bit) &&
            (t->threadFacts ? allPresent(heads, t->rule) : nodeFactsPresent(heads, *t)))
          cand[t->word] |= t->bit;
    }
    if (n == threadNode_ && inRun_ && running_ != threadNode_) [[unlikely]]
      threadFactAdded(p);
  }
  bool nodeFactsPresent(const ListHead* heads, const ProgramTables::RuleTrigger& t) const {
    const PredId* q = tables_.needs.data() + t.needsFrom;
    for (std::uint32_t i = 0; i < t.needCount; ++i)
      if (heads[q[i]].size == 0) return false;
    return true;
  }
  void threadFactAdded(PredId p);
  // Every body predicate has a fact at the node whose list heads are given (thread predicates:
  // at the thread node).
  bool allPresent(const ListHead* heads, std::uint32_t rule) const;
  bool hasCandidate(NodeId n) const;
  void reserveForAxioms();
  void startThreadNode();  // _init_thread and the special thread facts (§6.12)
  void sendThread(NodeId host, ThreadId t, PredId p, const Value* args, bool negative);
  void factRemoved(NodeId n, PredId p) {  // after the store lost a fact of p (inline: every consumption)
    if (db_->factCount(n, p) != 0) return;
    std::uint64_t* cand = candidates_.data() + std::size_t(n) * tables_.ruleWords;
    for (std::uint32_t i = tables_.triggersFrom[p], end = tables_.triggersFrom[p + 1]; i < end; ++i)
      cand[tables_.triggers[i].word] &= ~tables_.triggers[i].bit;
  }
  void collectGarbageNodes();
  // The established VM's deletions during the run (node_recycling.hpp): the nodes whose last
  // reference went in this run, and the node that ran.
  void freeDroppedNodes();
  bool unusedCreatedNode(NodeId n) const;
  void deleteCreatedNode(NodeId n);
  [[noreturn]] void fail(const std::exception& e, NodeId n, const std::string& where) const;

  // A fact for another node: into its mailbox (arguments retained), waking it up.
  // adopt: the caller's references to the boxed arguments go to the mailbox (no retain).
  void post(NodeId dest, PredId p, const Value* args, bool negative, bool adopt = false);

  struct PendingFact {  // a queued persistent derivation/retraction, or a buffered linear fact
    NodeId node;
    PredId pred;
    bool negative;
    std::uint32_t args;         // offset in the owning buffer's value array
    std::uint32_t delayMs = 0;  // sent facts: the `@+N` delay
    bool cancelled = false;     // queued: met its retraction before it ran (processPersistent)
  };
  bool cancelledByLaterRetraction(const PendingFact& e);
  void bufferSent(bool linear, const PendingFact& e) {
    if (linear)
      sentLinear_.push_back(e);
    else
      sentPersistent_.push_back(e);
  }
  void queuePersistent(NodeId n, PredId p, const Value* args, bool negative) {
    persistentQueue_.push_back({n, p, negative, std::uint32_t(persistentArgs_.size())});
    pushArgs(persistentArgs_, p, args);
    queuedRetractions_ += negative;
  }
  // Owned copies of argument lists (boxed values retained).
  // Appends the arguments to `to` (boxed values retained); returns their offset.
  std::uint32_t pushArgs(ValueBuffer& to, PredId p, const Value* args) {
    retainArgsInline(p, args);
    return to.append(args, tables_.arity[p]);
  }
  // retainArgs, with a fact of one boxed field retained here (8queens-12's messages, each with its
  // list: the call took 57 instructions a message).
  void retainArgsInline(PredId p, const Value* args) {
    if (const std::int8_t r = db_->referencePattern(p); r >= 0)
      heap_.retainObjectValue(args[r]);
    else if (r == ReferenceFields::kSeveralReferences)
      retainArgs(p, args);
  }
  [[gnu::noinline]] void retainArgs(PredId p, const Value* args);
  // The run-time errors of send(), out of line.
  [[noreturn, gnu::noinline]] void noSuchNode(PredId p, NodeId dest) const;
  [[noreturn, gnu::noinline]] void notANeighbour(PredId p, NodeId host, NodeId dest) const;
  void releaseArgs(PredId p, const Value* args);

  const Program& program_;
  MachineOptions options_;
  const ProgramTables tables_;  // per predicate and per rule, from the program
  NodeRecycling recycling_;     // before heap_, which counts node references in it
  Heap heap_;
  std::unique_ptr<Database> db_;
  std::unique_ptr<Interpreter> interp_;
  BuiltinContext builtinCtx_;
  Rng rng_;
  std::uint64_t stepsLeft_;  // options_.maxSteps counted down (no limit: more than a run takes)
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>>
      keyIndexes_;  // per predicate: (field, handle)
  void requestKeyIndex(PredId p, std::uint32_t field);
  void countStep() {
    if (__builtin_expect(--stepsLeft_ == 0, 0)) stepLimitReached();
  }
  void countSteps(std::uint64_t n) {  // n steps at once (the facts a rule run derived)
    if (__builtin_expect(n >= stepsLeft_, 0)) stepLimitReached();
    stepsLeft_ -= n;
  }
  [[noreturn, gnu::cold, gnu::noinline]] void stepLimitReached() const;
  SerialScheduler sched_;
  MachineStats stats_;
  bool stop_ = false;
  DerivationLog* derivations_ = nullptr;  // why a fact exists: off unless asked
  static constexpr NodeId kNoNode = 0xFFFFFFFFu;
  NodeId threadNode_ = kNoNode;  // the node of the one VM thread (§6.12)
  bool started_ = false;
  MachineHost* host_ = nullptr;
  ShardLink* shard_ = nullptr;
  bool ownGraphSerial_ = false;              // neither a host's block nor a shard (send's inline case)
  const NodeOwners* graphOwners_ = nullptr;  // shard_'s, when it has them
  const std::atomic<bool>* stopFlag_ = nullptr;
  std::atomic<bool> noStop_{false};  // stopFlag_ when the options give none: never set
  const std::atomic<bool>* safePointFlag_ = nullptr;
  // A safe point between every so many linear facts a node run takes in (deliverIncoming).
  static constexpr std::uint32_t kFactsBetweenSafePoints = 256;
  // A shard's node run takes in at most this many mailbox chunks (4 KiB: about 250 facts of two
  // words), in arrival order; the rest waits for the node's next run, right after. A node of
  // 8queens-12 took in up to 79,000 placements at once at -j 2: its fact tables, rule-run buffers
  // and sent facts grew with them, every access missed the cache, and rebalances waited. The
  // serial VM takes in the whole mailbox, as the established VM does; with threads, a node that
  // takes in the earliest arrivals first is a node that ran earlier.
  static constexpr std::uint32_t kChunksPerShardDelivery = 16;
  // A shard stores a linear fact it sends to one of its own nodes at once when that node holds
  // fewer facts of the predicate than this (and no mail): see storeSentLinear.
  static constexpr std::uint32_t kStoredOnArrivalBelow = 32;
  bool storedOnArrival(const PendingFact& e) const;
  ShardPlacement placement_;
  NodeId nextCreated_ = 0, createdEnd_ = 0;                   // a shard's block of ids for created nodes
  void postOrRoute(const PendingFact& e, const Value* args);  // takes over the references of args
  NodeId running_ = 0;
  bool inRun_ = false;
  bool nodeRunning_ = false;  // within runNode (its repeated runs included)
  NodeId initialNodes_ = 0;

  bool linearPosted_ = false;  // some linear fact went into a mailbox
  bool sentItself_ = false;    // the running node stored facts it sent itself (storeSentLinear)
  // While a node's mailbox is being delivered, facts the host gives that node (a robot's action
  // retracting its own `at`, run by a persistent rule during the delivery) wait here: the box is
  // released when the delivery ends, so a post into it would be lost. Posted right after.
  bool delivering_ = false;
  std::vector<PendingFact> heldBack_;
  ValueBuffer heldBackArgs_;

  // Candidate rules per node: a bitset of rulesWords_ words per node.
  LargeVector<std::uint64_t> candidates_;
  std::uint64_t* candidatesData_ = nullptr;  // candidates_.data(), read by native code (native_abi.h)

  std::unique_ptr<Mailboxes> mail_;

  // Within a rule run.
  ConsumedFacts consumed_;
  NativeArray<PendingFact> linearOut_;  // linear facts derived for the host, appended after the run
  ValueBuffer linearOutArgs_;
  std::vector<PendingFact> persistentQueue_;  // FIFO (§6.5)
  std::size_t persistentHead_ = 0;
  std::size_t queuedRetractions_ = 0;  // negative entries of the queue not yet run
  ValueBuffer persistentArgs_;
  // Facts sent to other nodes during a node run, posted when it ends: the persistent ones first
  // (the established VM posts them at once, so they precede every linear fact of the same run,
  // §6.4.4), each kind in sending order. Nothing can read a mailbox before the run ends, so
  // posting them together is unobservable, and it lets the posts prefetch their mailboxes.
  NativeArray<PendingFact> sentPersistent_;  // native code appends to it too (and to sentArgs_)
  NativeArray<PendingFact> sentLinear_;  // native code appends to it (and to sentArgs_)
  ValueBuffer sentArgs_;
  void postAll(std::span<const PendingFact> facts, const std::vector<std::uint32_t>* order);
  std::unique_ptr<detail::SendOrder> sendOrder_;
  // set-priority requests of the node run, applied when it ends (§5.7). The established VM keeps
  // them in a std::unordered_map keyed by node id (identity hash) and applies them in its
  // iteration order, which decides ties in the heap: the same container, fed the same way, gives
  // the same order. Its pool reuses the nodes, so the steady state allocates nothing.
  std::pmr::unsynchronized_pool_resource priorityPool_;
  std::pmr::unordered_map<std::uint64_t, double> priorityRequests_{&priorityPool_};
  std::vector<Value> triggerAdded_, triggerRemoved_;

  std::vector<Value> globals_;
  std::vector<Value> strings_;         // the string constants as heap strings
  std::vector<Value> args_;            // program arguments as heap strings
  std::vector<std::uint8_t> created_;  // per node: created by exists (may be collected)

  // SchedulerView (built-ins priority, cpu-id, ...).
  double priority(NodeId n) const override { return sched_.priority(n); }
  ThreadId owner(NodeId n) const override { return shard_ ? ownerOf(n) : 0; }
  std::int32_t staticNodes(ThreadId) const override;
  bool isStatic(NodeId n) const override { return sched_.isStatic(n); }
  std::int32_t queueSize(NodeId) const override { return std::int32_t(sched_.waiting()); }
  std::int32_t factsProved() const override { return std::int32_t(runDerived_); }
  std::int32_t factsConsumed() const override { return std::int32_t(runConsumed_); }
  std::int32_t threadCount() const override { return std::int32_t(placement_.threads); }
  std::uint64_t runDerived_ = 0, runConsumed_ = 0;
};

}  // namespace meldvm
