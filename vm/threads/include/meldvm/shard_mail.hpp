// The records shards send each other (worker threads through their channels, the simulated cores
// of `vsim --target multicore` through the simulated interconnect): a fact for a node, a
// coordination fact (§5.7) for a node, or a whole node moving to another shard (work stealing,
// set-cpu). One encoder and one decoder for both, so that a simulated chip moves exactly what
// the threads move. A record hands its boxed values over (Heap::share): shards of one process
// share them instead of copying them, and every shard's heap outlives the references the others
// hold (Machine::releaseAll on all of them first).
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/large_allocator.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

// Mapped from 128 KiB (large_allocator.hpp), so a large buffer given back returns its pages.
using MailBytes = LargeVector<std::uint8_t>;

// When a shard sends what it has for other shards: once this many bytes wait, or after this many
// node runs with something waiting, or when it runs out of nodes to run. The worker threads and
// the simulated chip both follow it, so the chip's node runs see the batches threads see.
struct BatchPolicy {
  static constexpr std::size_t kFlushBytes = 65536;
  static constexpr unsigned kFlushRuns = 64;
  // A buffer that grew past this (a rebalance moving nodes with their stored facts, or a long
  // node run's facts for one thread) is given back once used, unless the thread's recent batches
  // are as large (RecentBatches). Kept, every buffer on the way (the sender's, the channel's, the
  // receiver's, a move's scratch) held its largest size to the end of the run: 7.6 MB of
  // 8queens-12's 37.5 MB at -j 2, when moves still copied the waiting messages.
  static constexpr std::size_t kKeptBytes = 4 * kFlushBytes;
};

// Empties `buffer`, giving its memory back if it grew past keptBytes.
template <class Buffer>
void clearBuffer(Buffer& buffer, std::size_t keptBytes = BatchPolicy::kKeptBytes) {
  if (buffer.capacity() * sizeof(typename Buffer::value_type) > keptBytes)
    Buffer().swap(buffer);
  else
    buffer.clear();
}

// How large a thread's batch buffers stay while its batches stay large: twice the largest recent
// batch, which loses an eighth at each batch since, and at least BatchPolicy::kKeptBytes. A buffer
// given back is mapped afresh when it grows again: B2 n-queens 13 at -j 2 sends batches of ~370
// KB on average and took 25 K page faults (4 K serially), its unmaps stopping the other thread
// too. With this: 15 K, and 1.31 -> 1.17 s (2-core VM, medians of 7 interleaved runs), 3 MB more.
// Losing half at each batch kept too few (19 K faults); buffers kept up to 4 MiB whatever the
// batches cost B2 belief-propagation, whose large batches are few, 2 MB more at -j 2 (1.25x its
// serial memory) where this costs it 0.2 MB.
class RecentBatches {
 public:
  void sent(std::size_t bytes) {  // a batch sent or taken
    const std::size_t decayed = largest_ - largest_ / 8;
    largest_ = bytes > decayed ? bytes : decayed;
  }
  std::size_t keptBytes() const {
    return 2 * largest_ > BatchPolicy::kKeptBytes ? 2 * largest_ : BatchPolicy::kKeptBytes;
  }

 private:
  std::size_t largest_ = 0;
};

class ShardMail {
 public:
  explicit ShardMail(const Program& program);

  // A fact for node dest; `heap` is the sender's (its boxed values are shared, and the record takes
  // over the caller's references to them).
  void putFact(MailBytes& out, Heap& heap, NodeId dest, PredId p, const Value* args, bool negative);
  void putCoordination(MailBytes& out, NodeId n, Opcode op, double value);
  // Node n leaves `from` with its stored facts, waiting messages and scheduling state (it must be
  // out of from's queue: Machine::unqueueToGive or pickNodesToGive). moved: by set-cpu (the taker
  // pins it and gives it just-moved). The waiting messages stay in their mailbox chunks, which
  // pass to the taker: the shards' mailboxes must share one MailSlabs.
  void putNode(MailBytes& out, Machine& from, NodeId n, bool moved);

  struct Taken {
    std::uint64_t facts = 0, nodes = 0;
  };
  // Applies every record of `in` to shard `to`; counts what it took. Throws RuntimeError for a
  // coordination fact whose node does not exist.
  void apply(Machine& to, const MailBytes& in, Taken& taken);
  // The scratch space's memory.
  std::size_t bytesReserved() const {
    return args_.capacity() * sizeof(Value) + toShare_.capacity() * sizeof(Object*);
  }

 private:
  // A fact's boxed values shared for the record. adopt: the record takes over the caller's
  // references (else it retains its own). shareLater: the boxed values are listed there for
  // Heap::shareAll, not shared one by one.
  void handOver(Heap& heap, PredId p, const Value* args, bool adopt, std::vector<Object*>* shareLater);
  // handOver, then the fact's predicate word and arguments.
  void putArgs(MailBytes& out, Heap& heap, PredId p, const Value* args, bool negative, bool adopt,
               std::vector<Object*>* shareLater = nullptr);
  // use(pred, args, negative) returns whether it took over the record's references; if it throws,
  // it took nothing.
  template <class Use>
  void readFact(Machine& to, const MailBytes& in, std::size_t& pos, Use&& use);
  void takeNode(Machine& to, NodeId n, const MailBytes& in, std::size_t& pos);

  const Program& program_;
  std::vector<std::vector<std::uint32_t>> boxed_;  // per predicate: its boxed fields
  std::vector<Value> args_;                        // the reader's storage, reused
  std::vector<Object*> toShare_;                   // a moving node's boxed values, shared once all are listed
};

}  // namespace meldvm
