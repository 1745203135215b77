// The chunk table that the mailboxes of every shard of one run share (the worker threads of
// `meld -j N`, the cores of a simulated chip): a chunk id names the same chunk in each of them, so
// a node that moves to another shard takes its waiting messages along as a chain of chunk ids,
// not as a copy of every record (Mailboxes::detach, attach). A serial machine's mailboxes have a
// table of their own.
//
// Each shard allocates slabs in its own range of the table and frees them when its mailboxes go;
// a chunk may be used and recycled by any shard meanwhile, so every shard's mailboxes must go
// before the table, and none may read a chunk once another shard's mailboxes are gone.
// Entries are written once, by their range's shard, before any chunk of the slab is used; a chunk
// reaches another shard only through a synchronised hand-over (a move happens inside a barrier;
// spares pass under their lock), so reading an entry of another range needs no atomic.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <vector>

#include "meldvm/value.hpp"

namespace meldvm {

class MailSlabs {
 public:
  // Chunk ids are 32 bits: [slab | cell in slab] (a chunk is one or two cells), kCellBits of the
  // latter.
  static constexpr std::uint32_t kCellBits = 14;
  static constexpr std::uint32_t kSlabs = std::uint32_t(1) << (32 - kCellBits);
  static constexpr std::uint32_t kNoChunk = 0xFFFFFFFFu;  // the end of a chain

  explicit MailSlabs(std::uint32_t shards) {
    std::uint32_t bits = 0;
    while ((std::uint32_t(1) << bits) < shards) ++bits;
    if (bits >= 32 - kCellBits) throw std::length_error("meldvm: too many shards for the mailboxes");
    slabsPerShard_ = kSlabs >> bits;
    // calloc: the pages of the table are the system's zero pages until a shard writes its first
    // entries (a serial run touches one page of the 2 MiB).
    table_.reset(static_cast<Value**>(std::calloc(kSlabs, sizeof(Value*))));
    if (!table_) throw std::bad_alloc();
  }

  Value** table() const { return table_.get(); }

  // Free chunks that a shard had too many of, for whichever shard runs out (Mailboxes::release,
  // newChunk): chunks that move with nodes would otherwise gather on the taker's free list while
  // the giver maps new slabs. A shard takes the lock only when it has plenty or none.
  struct FreeChain {  // through the chunks' first words
    std::uint32_t head = kNoChunk, tail = kNoChunk, chunks = 0;
  };
  // Per size (small chunks, big chunks), chains of about kSpareBatchChunks chunks: a shard takes
  // one chain at a time, so a shard that needs one chunk does not take all of them.
  static constexpr std::uint32_t kSpareBatchChunks = 1024;
  struct Spares {
    std::mutex lock;
    std::vector<FreeChain> batches[2];  // the last one is being filled
    std::atomic<bool> any[2] = {};      // batches[i] is not empty (a hint: the lock decides)
  };
  Spares& spares() { return spares_; }
  // The range of slab numbers of `shard`.
  std::uint32_t firstSlab(std::uint32_t shard) const { return shard * slabsPerShard_; }
  std::uint32_t slabsPerShard() const { return slabsPerShard_; }

 private:
  struct Free {
    void operator()(Value** p) const noexcept { std::free(p); }
  };
  std::unique_ptr<Value*[], Free> table_;
  std::uint32_t slabsPerShard_ = kSlabs;
  Spares spares_;
};

}  // namespace meldvm
