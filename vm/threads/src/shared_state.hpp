// What the worker threads of one run share: the channels, the quiescence counter, the stop and
// error flags, and one cache line per thread for waking it up.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "channel.hpp"
#include "meldvm/shard.hpp"

namespace meldvm::threads {

struct SharedState {
  explicit SharedState(ThreadId threads)
      : threads(threads),
        channels(new Channel[std::size_t(threads) * threads]),
        gaveNodes(new std::atomic<bool>[std::size_t(threads) * threads]),
        perThread(new PerThread[threads]) {
    for (std::size_t i = 0; i < std::size_t(threads) * threads; ++i) gaveNodes[i].store(false);
    active.store(threads);
  }

  Channel& channel(ThreadId from, ThreadId to) { return channels[std::size_t(from) * threads + to]; }

  // Wakes thread t if it sleeps waiting for work (see Worker::waitForWork for the protocol).
  void wake(ThreadId t) {
    PerThread& p = perThread[t];
    p.signal.fetch_add(1);
    if (p.sleeping.load()) p.signal.notify_one();
  }
  void wakeAll() {
    for (ThreadId t = 0; t < threads; ++t) wake(t);
  }
  // Every thread joins a rebalance between two node runs (worker.cpp).
  void askForRebalance() {
    bool expected = false;
    if (rebalanceWanted.compare_exchange_strong(expected, true)) wakeAll();
  }
  void finish() {
    done.store(true);
    wakeAll();
  }
  void stopAll() {
    stop.store(true);
    wakeAll();
  }
  void fail(std::exception_ptr e) {
    {
      std::lock_guard<std::mutex> lock(errorLock);
      if (!error) error = e;
    }
    stopAll();
  }
  bool over() const { return done.load(std::memory_order_relaxed) || stop.load(std::memory_order_relaxed); }

  // The rebalancing barrier: every thread arrives, the last one lets them all go on. False if the
  // run ended meanwhile (stop-program, an error).
  bool arriveAndWait() {
    const std::uint32_t generation = barrierGeneration.load();
    if (barrierArrived.fetch_add(1) + 1 == threads) {
      barrierArrived.store(0);
      barrierGeneration.fetch_add(1);
      return true;
    }
    for (unsigned spin = 0; barrierGeneration.load() == generation; ++spin) {
      if (over()) return false;
      if (spin >= 64) std::this_thread::yield();
    }
    return true;
  }

  const ThreadId threads;
  // Quiescence: threads that are busy plus batches pushed and not yet taken. A thread going idle
  // takes itself off; one that finds a batch while idle counts itself back on before the batch
  // comes off. Only busy threads push batches, so once the count reaches zero it stays there:
  // the run is over.
  std::atomic<std::int64_t> active{0};
  std::atomic<bool> done{false}, stop{false};
  std::unique_ptr<Channel[]> channels;  // [from * threads + to]

  // Work stealing: a thread out of work asks for a rebalance, every thread joins it between
  // node runs (worker.cpp); support::StealPolicy says when the next may come.
  std::atomic<bool> rebalanceWanted{false};
  std::atomic<std::uint32_t> idleThreads{0};  // threads in waitForWork: a busy one with a queue asks for them
  std::atomic<std::int64_t> nextRebalanceNs{0};
  std::atomic<std::uint32_t> barrierArrived{0}, barrierGeneration{0};
  // set-cpu / set-affinity requests, carried out at the next rebalance: `moves` collects them
  // (under the lock), a rebalance plans with what it held when every thread had arrived.
  std::mutex movesLock;
  std::vector<std::pair<NodeId, ThreadId>> moves, plannedMoves;
  // [from * threads + to]: in this rebalance, thread `from` put nodes in its channel to `to`.
  std::unique_ptr<std::atomic<bool>[]> gaveNodes;

  struct alignas(64) PerThread {
    std::atomic<std::uint32_t> signal{0};
    std::atomic<bool> sleeping{false};
    std::atomic<std::int32_t> staticNodes{0};
    std::atomic<std::uint32_t> queued{0};  // nodes waiting to run, as of the thread's last node run
    std::atomic<float> idleShare{0};       // of the time since the last rebalance (set in one)
    std::atomic<bool> midRun{false};       // in a rebalance from a safe point of a node run
  };
  std::unique_ptr<PerThread[]> perThread;

  std::mutex errorLock;
  std::exception_ptr error;  // the first error of any thread
};

}  // namespace meldvm::threads
