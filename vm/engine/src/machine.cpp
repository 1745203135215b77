#include "meldvm/machine.hpp"

#include <algorithm>
#include <functional>
#include <ostream>
#include <sstream>

#include "interpreter.hpp"
#include "meldvm/arith.hpp"
#include "meldvm/bytecode_internal.hpp"
#include "meldvm/dump.hpp"
#include "meldvm/mailboxes.hpp"
#include "send_order.hpp"

namespace meldvm {

namespace {
const Value kNoArgs[1] = {};  // arguments of _init and just-moved (home only)
}  // namespace

Machine::Machine(const Program& program, MachineOptions options)
    : program_(program),
      options_(std::move(options)),
      tables_(program),
      recycling_(tables_.createsNodes && !options_.shard && !options_.host),
      heap_(program.types, recycling_.references()),
      db_(std::make_unique<Database>(program.predicates, heap_)),
      builtinCtx_(heap_),
      rng_(Rng::forThread(options_.placement.self)),
      sched_(program.scheduling) {
  host_ = options_.host;
  shard_ = options_.shard;
  ownGraphSerial_ = !host_ && !shard_;
  if (shard_) graphOwners_ = shard_->graphOwners();
  stopFlag_ = options_.stopFlag ? options_.stopFlag : &noStop_;
  safePointFlag_ = options_.shard ? options_.safePointFlag : nullptr;
  placement_ = options_.placement;
  if (shard_ && host_) throw std::invalid_argument("a Machine is either a shard or driven by a host");
  stepsLeft_ = options_.maxSteps ? options_.maxSteps + 1 : UINT64_MAX;
  if (options_.seed) rng_.state ^= support::splitmix64(options_.seed);
  builtinCtx_.rng = &rng_;
  builtinCtx_.sched = this;
  const std::size_t preds = program.predicates.size();
  // Indexes (§4.4 `index p/N`, and the look-ups of ITER_KEY): requested before any fact is stored.
  keyIndexes_.resize(preds);
  for (const auto& [p, field] : tables_.keyLookups) requestKeyIndex(p, field);
  for (const std::string& s : program.strings) strings_.push_back(heap_.makeString(s));
  for (const std::string& a : options_.args) args_.push_back(heap_.makeString(a));
  globals_.assign(program.globals.size(), Value());  // never resized: native code reads them in place
  interp_ = std::make_unique<Interpreter>(*this, program_, *db_, builtinCtx_, options.native);
  std::vector<std::vector<ArgWidth>> shapes(preds);
  for (PredId p = 0; p < preds; ++p)
    for (TypeId t : program.predicates[p].fields) shapes[p].push_back(argWidth(program.types.kind(t)));
  if (options_.shard && !options_.mailSlabs) throw std::invalid_argument("a shard needs the run's MailSlabs");
  mail_ = std::make_unique<Mailboxes>(shapes, options_.mailSlabs, options_.placement.self);
  sendOrder_ = std::make_unique<detail::SendOrder>();
  linearOutArgs_.reserve(1024);
  persistentArgs_.reserve(1024);
  // Native code appends to these while they have room (and calls the VM when they have none): room
  // from the first fact on, so that a short run's facts take the same path as a long run's. Only
  // on the VM's own graph and one thread, where native code's sends go there: a robot's block and a
  // thread's shard keep their footprint (their derived facts take the VM's path until it grew the
  // array).
  if (ownGraphSerial_) {
    sentLinear_.reserve(16);
    sentPersistent_.reserve(16);
    sentArgs_.reserve(64);
    linearOut_.reserve(16);
  }
}

Machine::~Machine() { releaseAll(); }

void Machine::releaseAll() {
  if (!db_) return;  // released already
  // The databases go first (they hold references into the heap), then what the machine owns.
  for (std::size_t i = persistentHead_; i < persistentQueue_.size(); ++i)
    if (!persistentQueue_[i].cancelled)
      releaseArgs(persistentQueue_[i].pred, persistentArgs_.data() + persistentQueue_[i].args);
  for (const PendingFact& e : sentPersistent_) releaseArgs(e.pred, sentArgs_.data() + e.args);
  for (const PendingFact& e : sentLinear_) releaseArgs(e.pred, sentArgs_.data() + e.args);
  mail_->forEachPending([&](PredId p, const Value* args) { releaseArgs(p, args); });
  for (std::size_t g = 0; g < globals_.size(); ++g) heap_.release(program_.globals[g].type, globals_[g]);
  for (Value s : strings_) heap_.release(TypeTable::kString, s);
  for (Value a : args_) heap_.release(TypeTable::kString, a);
  interp_.reset();
  db_.reset();
}

MemoryUse Machine::memoryUse() const {
  MemoryUse m;
  m.factTables = db_->tableBytes();
  m.listHeads = db_->headBytes();
  m.heaps = heap_.bytesReserved();
  m.mailboxes = mail_->bytesReserved();
  m.scheduling =
      candidates_.capacity() * sizeof(std::uint64_t) + created_.capacity() + sched_.bytesReserved();
  const std::size_t facts = consumed_.bytesReserved() +
                            (heldBack_.capacity() + linearOut_.capacity() + persistentQueue_.capacity() +
                             sentPersistent_.capacity() + sentLinear_.capacity()) *
                                sizeof(PendingFact);
  const std::size_t values = heldBackArgs_.bytesReserved() + linearOutArgs_.bytesReserved() +
                             persistentArgs_.bytesReserved() + sentArgs_.bytesReserved() +
                             (triggerAdded_.capacity() + triggerRemoved_.capacity()) * sizeof(Value);
  m.buffers = facts + values + sendOrder_->bytesReserved();
  return m;
}

bool Machine::hasWork(NodeId n) const { return !mail_->empty(n) || (sentItself_ && n == running_); }

// ---- set-up and the scheduler loop ----

void Machine::start() {
  if (started_) return;
  started_ = true;
  const NodeId n = std::max<NodeId>(NodeId(program_.nodeSourceIds.size()), options_.nodes);
  initialNodes_ = n;
  if (!shard_) placement_ = {0, 1, 0, n};
  if (placement_.endOwned > n || placement_.firstOwned > placement_.endOwned)
    throw std::invalid_argument("shard placement outside the graph");
  // §6.12: with thread predicates, every VM thread has a node of its own, ids n, n + 1, ...,
  // allocated before any node `exists` creates.
  const NodeId all = tables_.hasThreads ? n + placement_.threads : n;
  if (tables_.hasThreads) threadNode_ = n + placement_.self;
  db_->addNodes(all);
  candidates_.assign(std::size_t(all) * tables_.ruleWords, 0);
  candidatesData_ = candidates_.data();
  mail_->addNodes(all);
  created_.assign(all, 0);
  recycling_.grow(all);
  if (!program_.globalsInit.code.empty()) {
    try {
      interp_->run(program_.globalsInit, 0);
    } catch (const std::exception& e) {
      fail(e, 0, "the constants");
    }
  }
  reserveForAxioms();
  for (NodeId i = placement_.firstOwned; i < placement_.endOwned; ++i) initNode(i);
  sched_.start(n, placement_.firstOwned, placement_.endOwned);
  if (tables_.hasThreads) {
    // The thread nodes have scheduler entries but are served apart (runNext()).
    for (ThreadId t = 0; t < placement_.threads; ++t) sched_.addNode();
    startThreadNode();
  }
}

void Machine::initNode(NodeId n) {
  if (program_.initPredicate == Program::kNoPred) return;
  db_->addLinear(n, program_.initPredicate, kNoArgs);
  factAdded(n, program_.initPredicate);
}

void Machine::reserveForAxioms() {
  // Room up front for every fact the axiom blocks of this machine's nodes store spares the fact
  // tables and their hash tables growing step by step while millions of axioms go in.
  std::vector<std::size_t> facts(program_.predicates.size(), 0);
  const NodeId end = std::min<NodeId>(placement_.endOwned, NodeId(program_.nodeAxioms.size()));
  for (NodeId n = placement_.firstOwned; n < end; ++n)
    if (const std::uint32_t b = program_.nodeAxioms[n]; b != Program::kNoAxioms)
      detail::forEachAxiomStore(program_, program_.axiomCode(b),
                                [&](PredId p, std::size_t count) { facts[p] += count; });
  // A shard may take nodes from others later.
  const std::size_t slack = shard_ ? 64 : 0;
  for (PredId p = 0; p < facts.size(); ++p)
    if (facts[p] != 0 && !program_.predicates[p].action) db_->reserve(p, facts[p] + slack);
}

void Machine::startThreadNode() {
  const PredicateTable& preds = program_.predicates;
  auto find = [&](const char* name) {
    const PredId p = preds.find(name);
    return p < preds.size() && preds[p].thread ? p : Program::kNoPred;
  };
  if (const PredId p = find("_init_thread"); p != Program::kNoPred) {
    db_->addLinear(threadNode_, p, kNoArgs);
    factAdded(threadNode_, p);
  }
  // The special facts: the list of all threads, every other thread with its index, the leader.
  std::vector<Value> all;
  for (ThreadId t = 0; t < placement_.threads; ++t) all.push_back(Value::fromThread(t));
  if (const PredId p = find("thread-list"); p != Program::kNoPred) {
    const Value list = heap_.makeList(preds[p].fields[0], all);
    db_->derive(threadNode_, p, &list);
    heap_.release(preds[p].fields[0], list);
    factAdded(threadNode_, p);
  }
  if (const PredId p = find("other-thread"); p != Program::kNoPred)
    for (ThreadId t = 0; t < placement_.threads; ++t)
      if (t != placement_.self) {
        const Value args[2] = {Value::fromThread(t), Value::fromInt(std::int32_t(t))};
        db_->derive(threadNode_, p, args);
        factAdded(threadNode_, p);
      }
  if (const PredId p = find("leader-thread"); p != Program::kNoPred) {
    const Value leader = Value::fromThread(0);
    db_->derive(threadNode_, p, &leader);
    factAdded(threadNode_, p);
  }
}

void Machine::run() {
  start();
  while (!stop_ && runNext()) {
  }
  if (!stop_)
    collectGarbageNodes();
  else if (!shard_ && !host_)
    storeUndeliveredLinear();
}

// §6.13: after stop-program the established VM's dump shows the linear facts sent to nodes that
// never ran again (it stores them in the receiver as they arrive); persistent ones wait unseen.
void Machine::storeUndeliveredLinear() {
  for (NodeId n = 0; n < db_->nodeCount(); ++n) {
    if (!hasWork(n)) continue;
    mail_->forEach(
        n, [&](PredId) { return true; },
        [&](PredId p, bool, const Value* args) {
          if (tables_.isLinear[p]) db_->addLinear(n, p, args);
          releaseArgs(p, args);
        });
    mail_->release(n);
  }
}

bool Machine::runNext() {
  start();
  // §6.11: the heap, then the FIFO, then the thread node.
  NodeId node;
  if (sched_.pop(node)) {
    runNode(node);
    return true;
  }
  if (threadNode_ != kNoNode && (hasWork(threadNode_) || hasCandidate(threadNode_))) {
    runNode(threadNode_);
    return true;
  }
  return false;
}

void Machine::receive(NodeId n, PredId p, const Value* args, bool negative, bool adopt) {
  start();
  if (n >= db_->nodeCount() || (shard_ && !holdsNode(n)))
    throw RuntimeError("fact for node @" + std::to_string(n) + ", which does not exist");
  if (delivering_ && n == running_) [[unlikely]] {
    heldBack_.push_back(
        {n, p, negative,
         adopt ? heldBackArgs_.append(args, tables_.arity[p]) : pushArgs(heldBackArgs_, p, args)});
    return;
  }
  post(n, p, args, negative, adopt);
}

std::uint64_t Machine::runNode(NodeId n) {
  start();
  const std::uint64_t firedBefore = stats_.rulesFired;
  // §6.4.6: a node that sent facts to itself runs again at once, before any other node and
  // keeping its priority (on the VM's own graph; a host schedules its blocks itself).
  nodeRunning_ = true;  // what it sends itself wakes nothing: it runs again here
  do runOnce(n);
  while (!host_ && n != threadNode_ && !stopRequested() && hasWork(n));
  nodeRunning_ = false;
  if (!host_ && n != threadNode_) sched_.finished(n, hasWork(n));
  if (recycling_.counting() && unusedCreatedNode(n)) [[unlikely]]
    deleteCreatedNode(n);
  return stats_.rulesFired - firedBefore;
}

void Machine::runOnce(NodeId n) {
  // The FIFO says which nodes run next: fetch their mailbox entries and list heads three runs
  // ahead, then their first messages and first facts two runs ahead, so that a run rarely waits
  // for memory when it starts.
  NodeId ahead;
  if (sched_.peek(2, ahead)) {
    prefetchMailEntry(ahead);
    db_->prefetchNode(ahead);
    __builtin_prefetch(candidates_.data() + std::size_t(ahead) * tables_.ruleWords);
  }
  if (sched_.peek(1, ahead)) {
    mail_->prefetchMessages(ahead);
    db_->prefetchNodeFacts(ahead);
  }
  running_ = n;
  inRun_ = true;
  runDerived_ = runConsumed_ = 0;
  sentItself_ = false;  // what it sent itself is in its store: this run takes it in
  ++stats_.nodeRuns;
  if (!mail_->empty(n)) deliverIncoming(n);  // (on its own graph one machine stores linear facts on arrival)
  processPersistent();
  const bool withThread = threadNode_ != kNoNode && n != threadNode_;
  if (withThread) markThreadCandidates(n);
  std::uint64_t* cand = candidates_.data() + std::size_t(n) * tables_.ruleWords;
  // §6.4.2: the lowest-numbered candidate, of the node or of its thread, until none is left
  // (stop-program too lets the run finish, §6.13: only another thread's stop or a cancel cuts it).
  // (Most programs have at most 64 rules and no thread facts: one word, the node's, decides.)
  const bool oneWord = tables_.ruleWords == 1 && !withThread;
  while (!interrupted()) {
    std::uint32_t rule;
    if (oneWord) {
      if (!cand[0]) break;
      rule = std::uint32_t(__builtin_ctzll(cand[0]));
      cand[0] &= cand[0] - 1;
    } else if (rule = takeCandidate(n, cand, withThread); rule == ~0u) {
      break;
    }
    runRule(n, rule);
    finishRuleRun();
    // A long node run would hold up a rebalance until it ends: between two rules, the runtime may
    // deliver facts and move this shard's other nodes (never this one: movableNow).
    if (safePointFlag_ && safePointFlag_->load(std::memory_order_relaxed)) [[unlikely]]
      shard_->safePoint();
    cand = candidates_.data() + std::size_t(n) * tables_.ruleWords;  // exists may have grown the array
  }
  inRun_ = false;
  flushOutgoing();
  if (!priorityRequests_.empty()) applyPriorityRequests();
  if (recycling_.counting()) [[unlikely]]
    freeDroppedNodes();
}

// The lowest-numbered candidate rule of node n (cand: its words) or, with withThread, of its
// thread node, its bit cleared; ~0u when there is none. A rule of the thread node's own
// candidates runs with the running node as its host (@host, §6.12), as the established VM runs
// it; the candidate bit is the thread node's.
std::uint32_t Machine::takeCandidate(NodeId n, std::uint64_t* cand, bool withThread) {
  const std::uint64_t* threadCand =
      withThread ? candidates_.data() + std::size_t(threadNode_) * tables_.ruleWords : nullptr;
  std::uint32_t rule = ~0u;
  NodeId owner = n;
  for (std::uint32_t w = 0; w < tables_.ruleWords && rule == ~0u; ++w) {
    const std::uint64_t bits = cand[w] | (threadCand ? threadCand[w] : 0);
    if (!bits) continue;
    rule = w * 64 + std::uint32_t(__builtin_ctzll(bits));
    if (!(cand[w] & (std::uint64_t(1) << (rule % 64)))) owner = threadNode_;
  }
  if (rule == ~0u) return rule;
  std::uint64_t* ownerCand = candidates_.data() + std::size_t(owner) * tables_.ruleWords;
  ownerCand[rule / 64] &= ~(std::uint64_t(1) << (rule % 64));
  return rule;
}

// §6.12: while a normal node runs, its thread's facts are visible. The rules over node and thread
// facts are checked again (the thread's facts may have changed since this node last ran), and so
// are the thread's own rules (rule 1, rules over thread facts only): the established VM marks the
// thread's facts anew for each node, and their host, and what `A = @host` allows, is that node.
// Both compete with the node's rules by number.
void Machine::markThreadCandidates(NodeId n) {
  const ListHead* heads = db_->listHeads(n);
  std::uint64_t* cand = candidates_.data() + std::size_t(n) * tables_.ruleWords;
  for (std::uint32_t r : tables_.mixedRules)
    if (allPresent(heads, r)) cand[r / 64] |= std::uint64_t(1) << (r % 64);
  std::uint64_t* threadCand = candidates_.data() + std::size_t(threadNode_) * tables_.ruleWords;
  for (std::uint32_t r : tables_.threadRules)
    if (allPresent(heads, r)) threadCand[r / 64] |= std::uint64_t(1) << (r % 64);
}

void Machine::requestKeyIndex(PredId p, std::uint32_t field) {
  if (keyIndex(p, field) == ~0u) keyIndexes_[p].emplace_back(field, db_->requestIndex(p, field));
}

void Machine::stepLimitReached() const {
  throw RuntimeError("stopped after " + std::to_string(options_.maxSteps) +
                     " steps (the step limit: rule, process and loop runs, linear facts derived, "
                     "nodes created); the program may not terminate");
}

// runRule and finishRuleRun are runOnce's, inlined into its loop over the node's rules (with the
// interpreter's runInOwnFrame): heat-transfer 100 x 100 natively ran 3.1 % fewer instructions.
[[gnu::always_inline]] inline void Machine::runRule(NodeId n, std::uint32_t rule) {
  countStep();
  try {
    interp_->runRule(rule, n);
  } catch (const RuntimeError& e) {
    fail(e, n, "rule " + std::to_string(rule) + " (" + program_.rules[rule].block.label + ")");
  }
}

// A rule run that consumed a few facts unlinks them here; one that consumed many, or facts with
// lists (whose cells it fetches ahead), in unlinkConsumed. (That loop inlined here took 0.9 %
// more instructions on 8queens-12, whose rule runs consume thousands of facts each.)
[[gnu::always_inline]] inline void Machine::finishRuleRun() {
  if (const std::size_t n = consumed_.size(); n <= kConsumedInline && !tables_.linearLists) {
    for (std::size_t i = 0; i < n; ++i) unlinkOne(consumed_[i]);
    consumed_.clear();
  } else {
    unlinkConsumed();
  }
  if (!linearOut_.empty()) storeDerivedLinear();  // (many rule runs derive no linear fact here)
  processPersistent();
}

// A consumed fact's list dies with it when the fact held its last reference, and its death drops
// a reference to the next cell, consed long before and cold by now: a fifth of n-queens 13's
// native run waited there (Heap::destroy). So the consumptions fetch the first cell of a list
// sixteen facts ahead; the cells after it are the heap's (it puts off a dead cell's tail and
// fetches it meanwhile). Fetching the second and third cells here as well, through the cells
// fetched before, waited on those: with the heap's deferred tails, n-queens 13 native took
// 1.054 s without them against 1.094 s with them (2-core VM, medians of 9 interleaved runs).
// Inline in unlinkConsumed: a call per consumed fact took 0.8 % of 8queens-12's instructions.
namespace {
constexpr std::size_t kFirstCellAhead = 16;
}

[[gnu::always_inline]] inline void Machine::fetchListsOfConsumed(std::size_t i) const {
  if (i + kFirstCellAhead >= consumed_.size()) return;
  const ConsumedFacts::Fact& c = consumed_[i + kFirstCellAhead];
  if (const std::int32_t field = tables_.listField[c.pred]; field >= 0)
    __builtin_prefetch(db_->args(c.pred, c.fact)[field].asObject());
}

void Machine::unlinkConsumed() {
  for (std::size_t i = 0; i < consumed_.size(); ++i) {
    if (tables_.linearLists) fetchListsOfConsumed(i);
    unlinkOne(consumed_[i]);
  }
  consumed_.clear();
}

void Machine::storeDerivedLinear() {
  countSteps(linearOut_.size());  // a run that doubles the node's facts is bounded too
  for (const PendingFact& e : linearOut_) {
    const Value* args = linearOutArgs_.data() + e.args;
    db_->addLinearTrusted(e.node, e.pred, args);  // the buffer's references go to the fact
    factAdded(e.node, e.pred);
  }
  linearOut_.clear();
  linearOutArgs_.clear();
}

void Machine::fail(const std::exception& e, NodeId n, const std::string& where) const {
  throw RuntimeError("runtime error at node @" + std::to_string(n) + " in " + where + ": " + e.what());
}

// ---- candidate rules (§6.4.2) ----

bool Machine::allPresent(const ListHead* heads, std::uint32_t rule) const {
  for (PredId q : program_.rules[rule].bodyPredicates)
    if ((tables_.isThreadPred[q] ? db_->factCount(threadNode_, q) : heads[q].size) == 0) return false;
  return true;
}

bool Machine::hasCandidate(NodeId n) const {
  const std::uint64_t* cand = candidates_.data() + std::size_t(n) * tables_.ruleWords;
  for (std::uint32_t w = 0; w < tables_.ruleWords; ++w)
    if (cand[w]) return true;
  return false;
}

// A thread fact makes the thread node's own rules candidates (factAdded), and the rules mixing
// node and thread facts of the node that is running (others check them when they start a run).
void Machine::threadFactAdded(PredId p) {
  auto isCandidate = [](const std::uint64_t* c, std::uint32_t r) { return c[r / 64] >> (r % 64) & 1; };
  std::uint64_t* runningCand = candidates_.data() + std::size_t(running_) * tables_.ruleWords;
  const ListHead* runningHeads = db_->listHeads(running_);
  for (std::uint32_t r : tables_.rulesOf[p])
    if (tables_.isMixedRule[r] && !isCandidate(runningCand, r) && allPresent(runningHeads, r))
      runningCand[r / 64] |= std::uint64_t(1) << (r % 64);
}

// ---- what the interpreter calls ----

void Machine::retainArgs(PredId p, const Value* args) { db_->referenceFields(p).retain(heap_, args); }

void Machine::releaseArgs(PredId p, const Value* args) { db_->referenceFields(p).release(heap_, args); }

void Machine::derive(NodeId host, PredId p, const Value* args, bool negative) {
  const PredicateDesc& d = program_.predicates[p];
  if (d.action) {
    if (!negative) action(host, host, p, args);
    return;
  }
  if (!negative) {
    ++stats_.factsDerived;
    ++runDerived_;
  }
  if (d.linear) {
    if (negative) return;  // linear facts are never undone (§6.8)
    linearOut_.push_back({host, p, false, std::uint32_t(linearOutArgs_.size())});
    pushArgs(linearOutArgs_, p, args);
    return;
  }
  if (tables_.queuedPersistent[p]) {
    queuePersistent(host, p, args, negative);
    return;
  }
  const Change c = negative ? db_->retract(host, p, args) : db_->derive(host, p, args);
  if (c.added) factAdded(host, p);
  if (c.removed) factRemoved(host, p);
}

// A node's literal axioms come a predicate at a time, thousands of facts at start-up on a large
// graph: a plain persistent predicate stores them in one call to the store and checks the rules
// they trigger once (the candidate bits depend only on which predicates have facts).
void Machine::deriveEach(NodeId host, PredId p, const Value* args, std::uint32_t count) {
  const PredicateDesc& d = program_.predicates[p];
  if (d.action || d.linear || tables_.queuedPersistent[p]) {
    for (std::uint32_t i = 0; i < count; ++i) derive(host, p, args + std::size_t(i) * d.arity(), false);
    return;
  }
  stats_.factsDerived += count;
  runDerived_ += count;
  if (db_->deriveEach(host, p, args, count)) factAdded(host, p);
}

void Machine::sendAny(NodeId host, NodeId dest, PredId p, const Value* args, bool negative,
                      std::uint32_t delayMs) {
  // Delays need simulated time: only a host has it; on the VM's own graph a delayed fact is sent
  // at once.
  if (!host_) delayMs = 0;
  // On the VM's own graph a fact sent to the sending node itself is a message like any other
  // (§6.4.4): the established VM buffers it and delivers it when the node run ends, and the node
  // then runs again (runNode). A block of a host derives it at once.
  if (dest == host && delayMs == 0 && host_) return derive(host, p, args, negative);
  if (shard_) [[unlikely]] {
    const ThreadId owner = ownerOf(dest);
    if (owner == kNoThread) noSuchNode(p, dest);
    if (owner != placement_.self) {
      const PredicateDesc& d = program_.predicates[p];
      if (d.action) {  // on the VM's own graph an action only prints, at the deriving node
        if (!negative) action(host, dest, p, args);
        return;
      }
      if (d.linear && negative) return;
      if (!negative) ++stats_.factsDerived, ++runDerived_;
      ++stats_.factsSent;
      if (!d.linear) {
        // Into the batch for the owner now: the persistent facts of a run go out in the order they
        // were sent (postAll), which this keeps, and another thread sees them only when the batch
        // is flushed, between runs or in a rebalance, which takes every batch in before a node
        // moves. A copy and a second owner look-up less than waiting for the run's end.
        retainArgsInline(p, args);  // the record takes them over
        shard_->sendRemote(owner, dest, p, args, negative);
        return;
      }
      // The linear ones when the run ends, in the delivery order of send_order.hpp (postOrRoute).
      sentLinear_.push_back({dest, p, negative, std::uint32_t(sentArgs_.size())});
      pushArgs(sentArgs_, p, args);
      return;
    }
    // The common case of a shard, first: a linear fact for one of its own nodes, which may go
    // straight into the node's store when the run ends (storeSentLinear).
    if (tables_.plainLinear[p] && !negative && dest < db_->nodeCount() && db_->alive(dest)) {
      mail_->prefetchBox(dest);  // whether its mailbox is empty (storedOnArrival)
      return bufferSentLinear(dest, p, args);
    }
  }
  if (dest >= db_->nodeCount()) noSuchNode(p, dest);
  const PredicateDesc& d = program_.predicates[p];
  if (!host_ && d.linear && !shard_) {  // stored in dest when the run ends (storeSentLinear)
    db_->prefetchListHead(dest, p);
    prefetchStoreTarget(dest);
  } else if (!host_) {
    prefetchMailEntry(dest);  // posted when the run ends (flushOutgoing)
  }
  if (!db_->alive(dest)) noSuchNode(p, dest);
  if (d.action) {
    if (negative) return;
    if (delayMs == 0) return action(host, dest, p, args);
    // `setColor2(B, 3)@+1s` on a robot: the action runs on this block when the delay is over (its
    // runtime's timer brings the fact back here).
    sentLinear_.push_back({host, p, false, std::uint32_t(sentArgs_.size()), delayMs});
    pushArgs(sentArgs_, p, args);
    return;
  }
  if (host_ && dest != host && !host_->reachable(host, dest)) {
    // A retraction for a block that is no longer a neighbour is dropped: that block took back
    // what it had from this one when the link broke (BlockRuntime, inverse routes).
    if (negative) return;
    notANeighbour(p, host, dest);
  }
  if (d.linear && negative) return;
  if (!negative) {
    ++stats_.factsDerived;
    ++runDerived_;
  }
  ++stats_.factsSent;
  bufferSent(d.linear, {dest, p, negative, std::uint32_t(sentArgs_.size()), delayMs});
  pushArgs(sentArgs_, p, args);
}

void Machine::noSuchNode(PredId p, NodeId dest) const {
  throw RuntimeError("fact " + program_.predicates[p].name + " sent to node @" + std::to_string(dest) +
                     ", which does not exist");
}

void Machine::notANeighbour(PredId p, NodeId host, NodeId dest) const {
  throw RuntimeError("fact " + program_.predicates[p].name + " for node @" + std::to_string(dest) +
                     ", which is not a neighbour of @" + std::to_string(host));
}

void Machine::sendThread(NodeId host, ThreadId t, PredId p, const Value* args, bool negative) {
  if (t >= placement_.threads || threadNode_ == kNoNode)
    throw RuntimeError("fact " + program_.predicates[p].name + " for thread #T" + std::to_string(t) +
                       ", which does not exist (the VM runs " + std::to_string(placement_.threads) +
                       (placement_.threads == 1 ? " thread)" : " threads)"));
  if (!negative) ++stats_.factsDerived, ++runDerived_;
  const PredicateDesc& d = program_.predicates[p];
  if (t != placement_.self) {  // another thread's node: sent like a fact for a node of its own
    if (d.linear && negative) return;
    ++stats_.factsSent;
    bufferSent(d.linear, {initialNodes_ + t, p, negative, std::uint32_t(sentArgs_.size())});
    pushArgs(sentArgs_, p, args);
    return;
  }
  // The running thread: its node is visible to every node's rules, so its facts are stored
  // directly, as facts of the host are (linear ones when the rule run ends, persistent ones
  // through the queue).
  if (d.linear) {
    if (negative) return;
    linearOut_.push_back({threadNode_, p, false, std::uint32_t(linearOutArgs_.size())});
    pushArgs(linearOutArgs_, p, args);
    return;
  }
  queuePersistent(threadNode_, p, args, negative);
  (void)host;
}

void Machine::action(NodeId from, NodeId dest, PredId p, const Value* args) {
  if (host_) return host_->action(from, dest, p, args);
  // On the VM's own graph only write-string has a visible effect (§4.1.3); the robot runtime
  // executes the others (colours, motion).
  const PredicateDesc& d = program_.predicates[p];
  if (d.name == "write-string" && options_.output && d.arity() == 1)
    *options_.output << stringOf(args[0]) << '\n';
}

void Machine::updated(NodeId host, PredId p, FactRef f, const Value* args, bool moveToBack) {
  db_->updateLinearTrusted(host, p, f, args, moveToBack);
  factAdded(host, p);  // as consume + derive (§6.4.5): the rule may run again
  ++stats_.factsDerived;
  ++runDerived_;
}

NodeId Machine::appendNode(bool created) {
  const NodeId id = db_->nodeCount();
  growNodes(id + 1);
  created_[id] = created ? 1 : 0;
  initNode(id);
  return id;
}

void Machine::growNodes(NodeId end) {
  const NodeId count = end - db_->nodeCount();
  db_->addNodes(count);
  candidates_.resize(std::size_t(end) * tables_.ruleWords, 0);
  candidatesData_ = candidates_.data();
  mail_->addNodes(count);
  created_.resize(end, 0);
  recycling_.grow(end);
  for (NodeId i = 0; i < count; ++i) sched_.addNode();
}

NodeId Machine::newNode() {
  countStep();
  if (host_) throw RuntimeError("exists: a robot cannot create nodes (every node is a block)");
  NodeId id;
  if (shard_) {
    // A shard numbers its nodes from blocks of ids of its own (§6.10: 16384 per thread).
    if (nextCreated_ == createdEnd_) {
      NodeId count = 0;
      nextCreated_ = shard_->allocateNodeBlock(placement_.self, count);
      createdEnd_ = nextCreated_ + count;
      growNodes(createdEnd_);
    }
    id = nextCreated_++;
    created_[id] = 1;
    initNode(id);
  } else if (recycling_.reuse(id)) {
    db_->reviveNode(id);
    sched_.renewNode(id);
    created_[id] = 1;
    initNode(id);
  } else {
    id = appendNode(true);
  }
  // Not queued: a new node runs when it first receives work (§5.3.5), as in the established VM,
  // whose FIFO then holds it behind the nodes woken earlier in the same run.
  return id;
}

NodeId Machine::addHostNode() {
  start();
  return appendNode(false);
}

// ---- work stealing (threaded runs) ----

// The nodes to give are a band at the end of this shard's ids that faces the taker: it holds
// `max` of the queued nodes, and the idle nodes between them go too (up to kBandSlack times
// `max`; past that, only the queued ones). Shards start as contiguous ranges and programs number
// neighbours close together (§6.1's breadth-first numbering), so moving a band shifts the
// boundary between two shards, where moving only the queued nodes would scatter them and
// multiply the facts that cross threads.
std::vector<NodeId> Machine::pickNodesToGive(std::size_t max, bool highestIds) {
  constexpr std::size_t kBandSlack = 2;
  auto movable = [&](NodeId n) { return n < initialNodes_ && n != threadNode_ && movableNow(n); };
  std::vector<NodeId> nodes;
  sched_.queuedForSteal(nodes, movable);
  if (nodes.empty() || max == 0) return {};
  max = std::min(max, nodes.size());
  const auto cut = nodes.begin() + std::ptrdiff_t(max - 1);
  if (highestIds)
    std::nth_element(nodes.begin(), cut, nodes.end(), std::greater<NodeId>());
  else
    std::nth_element(nodes.begin(), cut, nodes.end());
  const NodeId edge = *cut;  // the band ends at the max-th queued node from the end
  nodes.clear();
  std::size_t idleLeft = max * kBandSlack;
  auto take = [&](NodeId n) {
    if (!sched_.held(n) || !movable(n) || sched_.isStatic(n)) return;
    if (!sched_.waiting(n)) {
      if (idleLeft == 0) return;
      --idleLeft;
    }
    sched_.unqueue(n);
    nodes.push_back(n);
  };
  if (highestIds) {
    for (NodeId n = initialNodes_; n-- > edge;) take(n);
    std::reverse(nodes.begin(), nodes.end());  // the taker queues them in id order
  } else {
    for (NodeId n = 0; n <= edge; ++n) take(n);
  }
  return nodes;
}

bool Machine::unqueueToGive(NodeId n) {
  if (n >= initialNodes_ || !ownedHere(n) || !movableNow(n)) return false;
  sched_.unqueue(n);
  return true;
}

void Machine::settleMovedNode(NodeId n) {
  setStatic(n, true);
  if (tables_.justMoved != Program::kNoPred) post(n, tables_.justMoved, kNoArgs, false);
}

Machine::GivenNode Machine::giveNode(NodeId n, const StoredFactVisitor& stored,
                                     const WaitingFactVisitor& waiting) {
  db_->forEachStored(n, stored);
  mail_->forEach(
      n, [](PredId) { return true; }, [&](PredId p, bool, const Value* args) { waiting(p, args); });
  const Mailboxes::Chain messages = mail_->detach(n);
  db_->clearNode(n);
  std::fill_n(candidates_.data() + std::size_t(n) * tables_.ruleWords, tables_.ruleWords, 0);
  const SerialScheduler::Carried state = sched_.carried(n);
  sched_.letGo(n);
  if (state.isStatic) setStatic(n, false);  // static here no more (the count of this thread)
  return {state, messages};
}

void Machine::takeNode(NodeId n, const SerialScheduler::Carried& state, const Mailboxes::Chain& waiting) {
  sched_.adopt(n, {state.prio, state.defaultPrio, false});
  if (state.isStatic) setStatic(n, true);  // counted for this thread (cpu-static)
  if (!waiting.empty()) {
    mail_->attach(n, waiting);
    linearPosted_ = true;  // (it may not be: the flag only spares a pass over the box)
  }
}

bool Machine::takeStoredFact(NodeId n, PredId p, const Value* args, std::uint32_t copies) {
  if (program_.predicates[p].linear) {
    db_->addLinearTrusted(n, p, args);
    factAdded(n, p);
    return true;
  }
  if (db_->derive(n, p, args, copies).added) factAdded(n, p);
  return false;
}

void Machine::takeNodeDone(NodeId n) {
  if (hasWork(n) || hasCandidate(n)) sched_.wake(n);
}

void Machine::dump(std::ostream& out) const { dumpDatabase(out, *db_); }

std::string Machine::dump() const {
  std::ostringstream s;
  dump(s);
  return s.str();
}

}  // namespace meldvm
