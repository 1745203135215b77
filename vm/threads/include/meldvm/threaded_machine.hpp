// The multicore target (`meld -j N`): a Meld program on N worker threads. Each thread owns a
// shard (a Machine with its own store, heap and scheduler, shard.hpp) and a contiguous range of
// the graph's nodes, as the established VM partitions them statically; thread t also has thread
// node N + t (§6.12). A fact for another thread's node goes through the channel of that
// pair of threads. The run ends by quiescence: no thread has work and no fact is in transit
// (one counter of busy threads and batches in transit, see worker.cpp), or by stop-program.
//
// For a program whose result does not depend on the order in which nodes run, the dump equals
// the serial VM's; the thread nodes (one per thread) and the ids of created nodes (blocks of
// 16384 per thread) are where a threaded dump differs by design.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "meldvm/machine.hpp"

namespace meldvm {

namespace threads {
class NodeDirectory;
class Worker;
struct SharedState;
}  // namespace threads

// What one worker thread did (meld --stats prints the table).
struct ThreadStats {
  std::uint64_t nodeRuns = 0, rulesFired = 0, factsDerived = 0, factsTried = 0;
  std::uint64_t factsOut = 0, factsIn = 0;  // facts sent to / received from other threads
  std::uint64_t bytesOut = 0;               // the records of the facts sent (shard_mail.hpp)
  std::uint64_t batchesOut = 0;             // channel pushes (each one or more facts)
  std::uint64_t waits = 0;                  // times the thread ran out of work
  std::uint64_t rebalances = 0;             // work-stealing rounds it took part in
  std::uint64_t midRunRebalances = 0;       // of those, joined from a safe point of a node run
  std::uint64_t nodesTaken = 0, nodesGiven = 0;
  std::uint64_t bytesMoved = 0;  // the records of the nodes it gave (their facts and messages)
  double busySeconds = 0, idleSeconds = 0, rebalanceSeconds = 0;
  // Of rebalanceSeconds, the time after every thread had arrived: moving nodes, not waiting for
  // the others to end their node runs.
  double rebalanceWorkSeconds = 0;
};

class ThreadedMachine {
 public:
  // `threads` >= 1; options as for a Machine (host must be null: robots run serially).
  ThreadedMachine(const Program& program, MachineOptions options, unsigned threads);
  ~ThreadedMachine();
  ThreadedMachine(const ThreadedMachine&) = delete;
  ThreadedMachine& operator=(const ThreadedMachine&) = delete;

  // Records each thread's timeline during run() (call before it) for writeProfile.
  void recordProfile() { profile_ = true; }
  // Runs to quiescence or stop-program. Throws RuntimeError (the first error of any thread).
  void run();
  // Ends the run from another thread as stop-program would (each thread stops after its current
  // rule); before run(), the run stops at once. Safe to call at any time, from any thread.
  void cancel();
  // The timelines as a Chrome trace-event file (Perfetto, chrome://tracing): per thread, spans
  // of node runs (coalesced: about 1 ms each), idle spans and steal spans (rebalances), and
  // counters of facts derived and queued nodes. Call after run() with recordProfile().
  void writeProfile(std::ostream& out) const;

  void dump(std::ostream& out) const;
  std::string dump() const;
  unsigned threads() const { return unsigned(workers_.size()); }
  MachineStats stats() const;  // all threads together
  std::vector<ThreadStats> threadStats() const;
  double wallSeconds() const { return wallSeconds_; }
  MemoryUse memoryUse() const;  // all threads together
  bool stopped() const;

 private:
  void collectGarbageNodes();
  std::vector<const Machine*> shards() const;

  const Program& program_;
  std::unique_ptr<threads::NodeDirectory> directory_;
  std::unique_ptr<threads::SharedState> shared_;
  std::unique_ptr<MailSlabs> mailSlabs_;  // outlives the workers' mailboxes
  std::vector<std::unique_ptr<threads::Worker>> workers_;
  std::mutex outputLock_;
  double wallSeconds_ = 0;
  bool profile_ = false;
};

}  // namespace meldvm
