#include "worker.hpp"

#include <algorithm>

namespace meldvm::threads {

namespace {

// A record in a channel: a header word (kind, negative flag, predicate or opcode), the node, then
// the fact's arguments (fact_codec.hpp) or the coordination value.
enum RecordKind : std::uint64_t { kFact = 0, kCoordination = 1 };

inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

Worker::Worker(const Program& program, MachineOptions options, ThreadId self, NodeDirectory& directory,
               SharedState& shared, std::mutex& outputLock)
    : program_(program), self_(self), directory_(directory), shared_(shared) {
  if (options.output) {
    lineOutput_ = std::make_unique<LineOutput>(*options.output, outputLock);
    output_ = std::make_unique<std::ostream>(lineOutput_.get());
    options.output = output_.get();
  }
  options.shard = this;
  options.placement = {self, directory.threads(), directory.firstOwned(self), directory.endOwned(self)};
  machine_ = std::make_unique<Machine>(program, std::move(options));
  outgoing_.resize(directory.threads());
  std::uint32_t arity = 1;
  for (PredId p = 0; p < program.predicates.size(); ++p) arity = std::max(arity, program.predicates[p].arity());
  args_.resize(arity);
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
  return s;
}

void Worker::loop() {
  const Clock::time_point start = Clock::now();
  try {
    machine_->start();
    for (;;) {
      if (shared_.stop.load(std::memory_order_relaxed)) {
        machine_->requestStop();
        break;
      }
      takeMail();
      if (machine_->runNext()) {
        if (outgoingWords_ != 0 && (outgoingWords_ >= kFlushWords || ++runsSinceFlush_ >= kFlushRuns)) flush();
        continue;
      }
      flush();
      if (takeMail()) continue;
      if (!waitForWork()) break;
    }
  } catch (...) {
    shared_.fail(std::current_exception());
  }
  stats_.busySeconds = std::max(0.0, secondsSince(start) - stats_.idleSeconds);
}

bool Worker::mailWaiting() const {
  for (ThreadId from = 0; from < shared_.threads; ++from)
    if (from != self_ && shared_.channel(from, self_).ready()) return true;
  return false;
}

bool Worker::takeMail() {
  bool any = false;
  for (ThreadId from = 0; from < shared_.threads; ++from) {
    if (from == self_) continue;
    Channel& ch = shared_.channel(from, self_);
    if (!ch.ready()) continue;
    const std::uint32_t batches = ch.take(incoming_);
    if (batches == 0) continue;
    decode(incoming_);
    incoming_.clear();
    shared_.active.fetch_sub(batches);  // cannot reach zero: this thread is busy
    any = true;
  }
  return any;
}

void Worker::decode(const Words& w) {
  Heap& heap = machine_->heap();
  for (std::size_t pos = 0; pos < w.size();) {
    const std::uint64_t header = w[pos];
    const NodeId node = NodeId(w[pos + 1]);
    pos += 2;
    if ((header & 1) == kCoordination) {
      const double value = Value::fromBits(w[pos++]).asFloat();
      if (!machine_->holdsNode(node))
        throw RuntimeError("coordination fact for node @" + std::to_string(node) + ", which does not exist");
      machine_->coordinateOwned(Opcode(header >> 32), node, value);
      continue;
    }
    const PredId p = PredId(header >> 32);
    const bool negative = (header >> 1) & 1;
    const PredicateDesc& d = program_.predicates[p];
    pos = decodeArgs(w, pos, d, heap, args_.data(), scratch_);
    ++stats_.factsIn;
    try {
      machine_->receive(node, p, args_.data(), negative);
    } catch (...) {
      releaseArgs(d, heap, args_.data());
      throw;
    }
    releaseArgs(d, heap, args_.data());
  }
}

void Worker::sendRemote(ThreadId to, NodeId, NodeId dest, PredId p, const Value* args, bool negative) {
  Words& w = outgoing_[to];
  const std::size_t before = w.size();
  w.push_back(kFact | (std::uint64_t(negative) << 1) | (std::uint64_t(p) << 32));
  w.push_back(dest);
  encodeArgs(w, program_.predicates[p], program_.types, args);
  outgoingWords_ += w.size() - before;
  ++stats_.factsOut;
}

void Worker::coordinateRemote(ThreadId to, Opcode op, NodeId n, double value) {
  Words& w = outgoing_[to];
  w.push_back(kCoordination | (std::uint64_t(op) << 32));
  w.push_back(n);
  w.push_back(Value::fromFloat(value).bits());
  outgoingWords_ += 3;
}

void Worker::flush() {
  if (outgoingWords_ == 0) return;
  for (ThreadId to = 0; to < shared_.threads; ++to) {
    Words& w = outgoing_[to];
    if (w.empty()) continue;
    shared_.active.fetch_add(1);  // before the batch can be taken
    shared_.channel(self_, to).push(w);
    shared_.wake(to);
    ++stats_.batchesOut;
  }
  outgoingWords_ = 0;
  runsSinceFlush_ = 0;
}

bool Worker::waitForWork() {
  const Clock::time_point start = Clock::now();
  ++stats_.waits;
  bool work = false;
  if (shared_.active.fetch_sub(1) == 1) {
    shared_.finish();  // the last busy thread and nothing in transit: quiescence
  } else {
    SharedState::PerThread& me = shared_.perThread[self_];
    for (unsigned spin = 0; !shared_.over(); ++spin) {
      if (mailWaiting()) {
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
        if (!mailWaiting() && !shared_.over()) me.signal.wait(seen);
        me.sleeping.store(false);
      }
    }
  }
  stats_.idleSeconds += secondsSince(start);
  return work;
}

}  // namespace meldvm::threads
