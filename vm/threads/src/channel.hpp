// Facts from one thread to another: one channel per ordered pair of threads, so a channel has one
// writer and one reader and facts keep their sending order. The sender appends whole batches of
// records (worker.cpp; meldvm/shard_mail.hpp) under the channel's lock; the receiver swaps
// the buffer out under the same lock. Nobody else ever takes that lock, and it is taken once per batch, not
// per fact. The two buffers trade places, so their capacity is reused: no allocation in the steady state
// (a buffer that grew past what recent batches needed is given back after use: RecentBatches).
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "meldvm/shard_mail.hpp"

namespace meldvm::threads {

using Bytes = MailBytes;

class Channel {
 public:
  // Appends `batch` and leaves it empty (its capacity, or the pending buffer's, is kept).
  void push(Bytes& batch) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_.empty())
      pending_.swap(batch);
    else
      pending_.insert(pending_.end(), batch.begin(), batch.end());
    batch.clear();
    ++batches_;
    ready_.store(true, std::memory_order_release);
  }
  // Cheap check without the lock (a hint: take() decides).
  bool ready() const { return ready_.load(std::memory_order_acquire); }
  // Moves what is pending into `into` (which must be empty); returns how many batches that was.
  std::uint32_t take(Bytes& into) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::uint32_t batches = batches_;
    if (batches == 0) return 0;
    pending_.swap(into);
    batches_ = 0;
    ready_.store(false, std::memory_order_relaxed);
    return batches;
  }

 private:
  std::mutex mutex_;
  Bytes pending_;
  std::uint32_t batches_ = 0;
  std::atomic<bool> ready_{false};
};

}  // namespace meldvm::threads
