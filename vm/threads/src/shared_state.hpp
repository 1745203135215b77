// What the worker threads of one run share: the channels, the quiescence counter, the stop and
// error flags, and one cache line per thread for waking it up.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>

#include "channel.hpp"
#include "meldvm/shard.hpp"

namespace meldvm::threads {

struct SharedState {
  explicit SharedState(ThreadId threads)
      : threads(threads), channels(new Channel[std::size_t(threads) * threads]), perThread(new PerThread[threads]) {
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

  const ThreadId threads;
  // Quiescence: threads that are busy plus batches pushed and not yet taken. A thread going idle
  // takes itself off; one that finds a batch while idle counts itself back on before the batch
  // comes off. Only busy threads push batches, so once the count reaches zero it stays there:
  // the run is over.
  std::atomic<std::int64_t> active{0};
  std::atomic<bool> done{false}, stop{false};
  std::unique_ptr<Channel[]> channels;  // [from * threads + to]

  struct alignas(64) PerThread {
    std::atomic<std::uint32_t> signal{0};
    std::atomic<bool> sleeping{false};
    std::atomic<std::int32_t> staticNodes{0};
  };
  std::unique_ptr<PerThread[]> perThread;

  std::mutex errorLock;
  std::exception_ptr error;  // the first error of any thread
};

}  // namespace meldvm::threads
