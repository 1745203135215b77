#include "worker.hpp"

#include <algorithm>

namespace meldvm::threads {

namespace {

inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
std::int64_t nowNanos() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

}  // namespace

Worker::Worker(const Program& program, MachineOptions options, ThreadId self, NodeDirectory& directory,
               SharedState& shared, std::mutex& outputLock)
    : program_(program),
      self_(self),
      directory_(directory),
      shared_(shared),
      stealing_(!program.scheduling.staticNodes && directory.threads() > 1),
      mail_(program) {
  if (options.output) {
    lineOutput_ = std::make_unique<LineOutput>(*options.output, outputLock);
    output_ = std::make_unique<std::ostream>(lineOutput_.get());
    options.output = output_.get();
  }
  options.shard = this;
  options.stopFlag = &shared.stop;
  options.safePointFlag = &shared.rebalanceWanted;
  options.placement = {self, directory.threads(), directory.firstOwned(self), directory.endOwned(self)};
  machine_ = std::make_unique<Machine>(program, std::move(options));
  outgoing_.resize(directory.threads());
}

Worker::~Worker() {
  join();
  machine_.reset();  // before the output it writes to
}

ThreadStats Worker::stats() const {
  ThreadStats s = stats_;
  const MachineStats& m = machine_->stats();
  s.nodeRuns = m.nodeRuns;
  s.rulesFired = m.rulesFired;
  s.factsDerived = m.factsDerived;
  s.factsTried = m.factsTried;
  return s;
}

void Worker::loop() {
  const Clock::time_point start = Clock::now();
  windowStart_ = start;
  try {
    machine_->start();
    for (;;) {
      if (shared_.stop.load(std::memory_order_relaxed)) {
        machine_->requestStop();
        break;
      }
      if (shared_.rebalanceWanted.load(std::memory_order_relaxed)) rebalance();
      takeMail();
      // What waits behind the node about to run, for a thread that runs out meanwhile (it may
      // ask for a rebalance, which this thread joins from a safe point of the run).
      if (const auto waiting = std::uint32_t(machine_->waitingNodes()); waiting > 1)
        shared_.perThread[self_].queued.store(waiting - 1, std::memory_order_relaxed);
      if (machine_->runNext()) {
        if (!deferredMoves_.empty()) [[unlikely]] {  // set-cpu of a node that was running then
          for (const auto& [n, to] : deferredMoves_) requestMove(n, to);
          deferredMoves_.clear();
        }
        const auto queued = std::uint32_t(machine_->waitingNodes());
        shared_.perThread[self_].queued.store(queued, std::memory_order_relaxed);
        if (queued >= kStealableQueue && shared_.idleThreads.load(std::memory_order_relaxed) != 0)
          offerWork();
        if (profile_)
          profile_->nodeRun(machine_->stats().factsDerived, stats_.factsIn, machine_->waitingNodes());
        if (outgoingBytes_ != 0 && (outgoingBytes_ >= kFlushBytes || ++runsSinceFlush_ >= kFlushRuns))
          flush();
        continue;
      }
      flush();
      if (takeMail()) continue;
      shared_.perThread[self_].queued.store(0, std::memory_order_relaxed);
      if (requestRebalance()) continue;
      if (!waitForWork()) break;
    }
  } catch (...) {
    shared_.fail(std::current_exception());
  }
  if (profile_) profile_->finish(machine_->stats().factsDerived, stats_.factsIn);
  stats_.busySeconds = std::max(0.0, secondsSince(start) - stats_.idleSeconds);
}

MemoryUse Worker::memoryUse() const {
  MemoryUse m = machine_->memoryUse();
  m.buffers += incoming_.capacity() + mail_.bytesReserved();
  for (const Bytes& b : outgoing_) m.buffers += b.capacity();
  return m;
}

bool Worker::mailWaiting() const {
  for (ThreadId from = 0; from < shared_.threads; ++from)
    if (from != self_ && shared_.channel(from, self_).ready()) return true;
  return false;
}

bool Worker::takeMail() {
  bool any = false;
  for (ThreadId from = 0; from < shared_.threads; ++from)
    if (from != self_ && shared_.channel(from, self_).ready()) any |= takeFrom(from);
  return any;
}

bool Worker::takeFrom(ThreadId from) {
  const std::uint32_t batches = shared_.channel(from, self_).take(incoming_);
  if (batches == 0) return false;
  recentBatches_.sent(incoming_.size());
  decode(incoming_);
  clearBuffer(incoming_, recentBatches_.keptBytes());
  shared_.active.fetch_sub(batches);  // cannot reach zero: this thread is busy
  return true;
}

// Phase 4 of a rebalance: the nodes given to this thread. Only the channels that carry some: the
// others may already hold facts sent after phase 3 (their senders went on), possibly for a node
// still on its way here, and the next takeMail takes them once every given node is in.
void Worker::takeGivenNodes() {
  for (ThreadId from = 0; from < shared_.threads; ++from) {
    std::atomic<bool>& gave = shared_.gaveNodes[std::size_t(from) * shared_.threads + self_];
    if (!gave.load(std::memory_order_relaxed)) continue;
    gave.store(false, std::memory_order_relaxed);
    takeFrom(from);
  }
}

void Worker::decode(const Bytes& in) {
  ShardMail::Taken taken;
  mail_.apply(*machine_, in, taken);
  stats_.factsIn += taken.facts;
  stats_.nodesTaken += taken.nodes;
}

void Worker::sendRemote(ThreadId to, NodeId dest, PredId p, const Value* args, bool negative) {
  Bytes& out = outgoing_[to];
  const std::size_t before = out.size();
  mail_.putFact(out, machine_->heap(), dest, p, args, negative);
  outgoingBytes_ += out.size() - before;
  stats_.bytesOut += out.size() - before;
  ++stats_.factsOut;
}

void Worker::coordinateRemote(ThreadId to, Opcode op, NodeId n, double value) {
  Bytes& out = outgoing_[to];
  const std::size_t before = out.size();
  mail_.putCoordination(out, n, op, value);
  outgoingBytes_ += out.size() - before;
}

void Worker::flush() {
  if (outgoingBytes_ == 0) return;
  for (ThreadId to = 0; to < shared_.threads; ++to) {
    Bytes& w = outgoing_[to];
    if (w.empty()) continue;
    shared_.active.fetch_add(1);  // before the batch can be taken
    recentBatches_.sent(w.size());
    shared_.channel(self_, to).push(w);
    clearBuffer(w, recentBatches_.keptBytes());  // push() left it empty, maybe with a large capacity
    shared_.wake(to);
    ++stats_.batchesOut;
  }
  outgoingBytes_ = 0;
  runsSinceFlush_ = 0;
}

bool Worker::waitForWork() {
  const Clock::time_point start = Clock::now();
  ++stats_.waits;
  shared_.idleThreads.fetch_add(1);
  if (profile_) profile_->pauseBegin(machine_->stats().factsDerived, stats_.factsIn);
  bool work = false;
  if (shared_.active.fetch_sub(1) == 1) {
    shared_.finish();  // the last busy thread and nothing in transit: quiescence
  } else {
    SharedState::PerThread& me = shared_.perThread[self_];
    for (unsigned spin = 0; !shared_.over(); ++spin) {
      if (mailWaiting() || shared_.rebalanceWanted.load()) {
        shared_.active.fetch_add(1);  // busy again, before the batch's own count comes off
        work = true;
        break;
      }
      if (spin < 64) {
        cpuRelax();
      } else if (spin < 128) {
        std::this_thread::yield();
      } else {
        // Sleep until woken. A sender pushes, bumps `signal`, then looks at `sleeping`; here
        // `signal` is read before `sleeping` is set and the mail checked again, so a push cannot
        // slip between the check and the wait unnoticed.
        const std::uint32_t seen = me.signal.load();
        me.sleeping.store(true);
        if (!mailWaiting() && !shared_.over() && !shared_.rebalanceWanted.load()) me.signal.wait(seen);
        me.sleeping.store(false);
      }
    }
  }
  shared_.idleThreads.fetch_sub(1);
  stats_.idleSeconds += secondsSince(start);
  if (profile_) profile_->pauseEnd(ProfileRecorder::Kind::Idle);
  return work;
}

// ---- work stealing ----
//
// Shards own their nodes' facts, so a stolen node moves: its facts and waiting messages go to the
// thief's store. That is only safe when no fact for it is on its way, so nodes move inside a
// barrier: every thread flushes what it has for others and stops sending (phase 1), takes in
// everything sent to it (2: nothing is in transit now), the most loaded threads hand half the
// difference of their queues to the least loaded ones and the owner table changes (3), the
// takers store what they received (4) while the other threads go on: a taker reads only the
// channels that carry its new nodes before it takes any other mail, so a fact sent meanwhile
// never reaches a node before the node does. Then every fact sent goes to the new owner, and
// the order of the facts from one node to another is kept across the move. (Phase 4 had every
// thread wait for the takers: on pagerank-movies at -j 2 the giver then sat idle for as long
// as packing had taken, 0.6 to 3.6 ms a rebalance.)

bool Worker::requestRebalance() {
  if (!stealing_) return false;
  std::uint32_t longest = 0;
  for (ThreadId t = 0; t < shared_.threads; ++t)
    if (t != self_) longest = std::max(longest, shared_.perThread[t].queued.load(std::memory_order_relaxed));
  if (longest < kStealableQueue) return false;
  if (nowNanos() < shared_.nextRebalanceNs.load()) return false;
  shared_.askForRebalance();
  return true;
}

// A thread with nodes waiting sees another thread idle: it asks for the rebalance itself (the
// idle thread looked before this queue grew, and now sleeps).
void Worker::offerWork() {
  if (!stealing_ || shared_.rebalanceWanted.load(std::memory_order_relaxed)) return;
  if (nowNanos() < shared_.nextRebalanceNs.load()) return;
  shared_.askForRebalance();
}

// A node run that is long (thousands of rules) would keep every other thread waiting in the
// rebalance's first barrier: it joins from between two of its rules instead, gives nodes if it
// has the most, but takes none (its node's run goes on afterwards).
void Worker::safePoint() {
  if (shared_.rebalanceWanted.load(std::memory_order_relaxed)) rebalance(true);
}

void Worker::rebalance(bool midRun) {
  const Clock::time_point start = Clock::now();
  ++stats_.rebalances;
  stats_.midRunRebalances += midRun;
  if (profile_) profile_->pauseBegin(machine_->stats().factsDerived, stats_.factsIn);
  const std::uint64_t takenBefore = stats_.nodesTaken;
  struct EndSpan {  // the steal span ends however the rebalance does
    Worker& w;
    std::uint64_t before;
    ~EndSpan() {
      if (w.profile_) w.profile_->pauseEnd(ProfileRecorder::Kind::Steal, w.stats_.nodesTaken - before);
    }
  } endSpan{*this, takenBefore};
  flush();
  if (!shared_.arriveAndWait()) return;             // 1
  const Clock::time_point allThere = Clock::now();  // the cost of a rebalance starts here
  if (self_ == 0) {
    shared_.rebalanceWanted.store(false);
    std::lock_guard<std::mutex> lock(shared_.movesLock);
    shared_.plannedMoves.clear();
    shared_.plannedMoves.swap(shared_.moves);
  }
  takeMail();
  shared_.perThread[self_].queued.store(std::uint32_t(machine_->waitingNodes()));
  shared_.perThread[self_].midRun.store(midRun);
  publishIdleShare(start, allThere);
  if (!shared_.arriveAndWait()) return;  // 2
  const std::uint64_t givenBefore = stats_.nodesGiven;
  planMoves();
  // Before the takers store what they were given: the run's peak memory is both shards' together.
  // Between node runs only: a run stopped at a safe point may hold slots it has just freed.
  if (!midRun && stats_.nodesGiven != givenBefore) machine_->releaseFreePages();
  flush();
  if (!shared_.arriveAndWait()) return;  // 3
  takeGivenNodes();
  shared_.perThread[self_].queued.store(std::uint32_t(machine_->waitingNodes()));
  const double seconds = secondsSince(start);
  stats_.rebalanceSeconds += seconds;
  stats_.rebalanceWorkSeconds += secondsSince(allThere);
  windowStart_ = Clock::now();
  idleAtWindowStart_ = stats_.idleSeconds;
  if (self_ == 0) {
    const double cost = secondsSince(allThere) * 1e9;
    shared_.nextRebalanceNs.store(nowNanos() + support::StealPolicy::nextRebalanceAfter(cost));
  }
}

// Phase 3 of a rebalance: the same plan on every thread. set-cpu / set-affinity first (every
// thread reads the list; a node that is running now moves at the next rebalance); then the i-th
// most loaded thread gives to the i-th least loaded that is not in the middle of a node run.
void Worker::planMoves() {
  std::vector<ThreadId> order(shared_.threads);
  std::vector<std::uint32_t> load(shared_.threads);
  std::vector<double> idle(shared_.threads);
  std::vector<bool> busy(shared_.threads);
  for (ThreadId t = 0; t < shared_.threads; ++t) {
    order[t] = t, load[t] = shared_.perThread[t].queued.load();
    idle[t] = shared_.perThread[t].idleShare.load();
    busy[t] = shared_.perThread[t].midRun.load();
  }
  std::stable_sort(order.begin(), order.end(), [&](ThreadId a, ThreadId b) { return load[a] > load[b]; });
  for (const auto& [n, to] : shared_.plannedMoves) {
    if (to == self_ || directory_.ownerOf(n) != self_) continue;
    if (machine_->unqueueToGive(n))
      giveNode(to, n, true);
    else if (!machine_->movableNow(n))  // running now (a safe point): asked again after its run
      deferredMoves_.emplace_back(n, to);
  }
  for (std::size_t giver = 0, taker = order.size(); stealing_ && giver + 1 < taker;) {
    if (busy[order[taker - 1]]) {
      --taker;
      continue;
    }
    if (order[giver] == self_)
      giveNodes(order[taker - 1],
                support::StealPolicy::nodesToGive(load[order[giver]], load[order[taker - 1]],
                                                  idle[order[giver]], idle[order[taker - 1]]));
    ++giver, --taker;
  }
}

// The share of the time since the last rebalance this thread had nothing to run: its idle spans
// and its wait in this rebalance's first barrier.
void Worker::publishIdleShare(Clock::time_point arrived, Clock::time_point allThere) {
  const double window = std::chrono::duration<double>(allThere - windowStart_).count();
  const double idle =
      stats_.idleSeconds - idleAtWindowStart_ + std::chrono::duration<double>(allThere - arrived).count();
  shared_.perThread[self_].idleShare.store(float(support::StealPolicy::idleShare(idle, window)));
}

void Worker::giveNodes(ThreadId to, std::size_t count) {
  for (NodeId n : machine_->pickNodesToGive(count, to > self_)) giveNode(to, n, false);
}

void Worker::requestMove(NodeId n, ThreadId to) {
  {
    std::lock_guard<std::mutex> lock(shared_.movesLock);
    shared_.moves.emplace_back(n, to);
  }
  shared_.askForRebalance();  // no waiting for the next allowed rebalance: the program asked
}

void Worker::giveNode(ThreadId to, NodeId n, bool moved) {
  shared_.gaveNodes[std::size_t(self_) * shared_.threads + to].store(true, std::memory_order_relaxed);
  Bytes& out = outgoing_[to];
  const std::size_t before = out.size();
  mail_.putNode(out, *machine_, n, moved);
  directory_.moveNode(n, to);
  ++stats_.nodesGiven;
  stats_.bytesMoved += out.size() - before;
  outgoingBytes_ += out.size() - before;
}

}  // namespace meldvm::threads
