#include "worker.hpp"

#include <algorithm>
#include <cstring>

namespace meldvm::threads {

namespace {

// A record in a channel: its kind (u8), the node (u32), then for a fact its length (u32) and the
// fact as meldvm/fact_codec.hpp encodes it, for a coordination fact the opcode (u32) and the
// value (f64). Native byte order: the bytes never leave the process.
enum RecordKind : std::uint8_t { kFact = 0, kCoordination = 1 };

template <class T>
void put(Bytes& out, T v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}
template <class T>
T get(const Bytes& in, std::size_t& pos) {
  T v;
  std::memcpy(&v, in.data() + pos, sizeof(T));
  pos += sizeof(T);
  return v;
}

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
  options.stopFlag = &shared.stop;
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
        if (profile_) profile_->nodeRun(machine_->stats().factsDerived, stats_.factsIn, machine_->waitingNodes());
        if (outgoingBytes_ != 0 && (outgoingBytes_ >= kFlushBytes || ++runsSinceFlush_ >= kFlushRuns)) flush();
        continue;
      }
      flush();
      if (takeMail()) continue;
      if (!waitForWork()) break;
    }
  } catch (...) {
    shared_.fail(std::current_exception());
  }
  if (profile_) profile_->finish(machine_->stats().factsDerived, stats_.factsIn);
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

void Worker::decode(const Bytes& in) {
  Heap& heap = machine_->heap();
  for (std::size_t pos = 0; pos < in.size();) {
    const auto kind = get<std::uint8_t>(in, pos);
    const NodeId node = get<std::uint32_t>(in, pos);
    if (kind == kCoordination) {
      const auto op = Opcode(get<std::uint32_t>(in, pos));
      const double value = get<double>(in, pos);
      if (!machine_->holdsNode(node))
        throw RuntimeError("coordination fact for node @" + std::to_string(node) + ", which does not exist");
      machine_->coordinateOwned(op, node, value);
      continue;
    }
    const auto length = get<std::uint32_t>(in, pos);
    decodeFact(in.data() + pos, length, program_.predicates, heap, fact_);
    pos += length;
    ++stats_.factsIn;
    const PredicateDesc& d = program_.predicates[fact_.pred];
    auto release = [&] {
      for (std::uint32_t i = 0; i < d.arity(); ++i) heap.release(d.fields[i], fact_.args[i]);
    };
    try {
      machine_->receive(node, fact_.pred, fact_.args.data(), fact_.negative);
    } catch (...) {
      release();
      throw;
    }
    release();
  }
}

void Worker::sendRemote(ThreadId to, NodeId, NodeId dest, PredId p, const Value* args, bool negative) {
  Bytes& out = outgoing_[to];
  const std::size_t before = out.size();
  put<std::uint8_t>(out, kFact);
  put<std::uint32_t>(out, dest);
  put<std::uint32_t>(out, 0);  // the length, once known
  const std::size_t start = out.size();
  encodeFact(out, program_.predicates, p, args, negative);
  const auto length = std::uint32_t(out.size() - start);
  std::memcpy(out.data() + start - sizeof length, &length, sizeof length);
  outgoingBytes_ += out.size() - before;
  ++stats_.factsOut;
}

void Worker::coordinateRemote(ThreadId to, Opcode op, NodeId n, double value) {
  Bytes& out = outgoing_[to];
  put<std::uint8_t>(out, kCoordination);
  put<std::uint32_t>(out, n);
  put<std::uint32_t>(out, std::uint32_t(op));
  put<double>(out, value);
  outgoingBytes_ += 17;
}

void Worker::flush() {
  if (outgoingBytes_ == 0) return;
  for (ThreadId to = 0; to < shared_.threads; ++to) {
    Bytes& w = outgoing_[to];
    if (w.empty()) continue;
    shared_.active.fetch_add(1);  // before the batch can be taken
    shared_.channel(self_, to).push(w);
    shared_.wake(to);
    ++stats_.batchesOut;
  }
  outgoingBytes_ = 0;
  runsSinceFlush_ = 0;
}

bool Worker::waitForWork() {
  const Clock::time_point start = Clock::now();
  ++stats_.waits;
  if (profile_) profile_->idleBegin(machine_->stats().factsDerived, stats_.factsIn);
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
  if (profile_) profile_->idleEnd();
  return work;
}

}  // namespace meldvm::threads
