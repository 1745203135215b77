// Facts in transit to nodes (spec §6.6): per node, the messages not yet taken in, in arrival
// order. A node's messages live in chains of fixed-size chunks (256 bytes), so taking in a run's
// worth of messages touches a few cache lines in a row instead of one scattered record per
// message. A record takes 1 + arity words of its own predicate, so small facts pack densely: a
// wide flood keeps millions of messages in flight, and every word of them is written and read
// back from memory. Chunks come from slabs that never move (growing copies nothing) and are
// recycled through a free list, so the steady state allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/large_allocator.hpp"
#include "meldvm/predicate.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

class Mailboxes {
 public:
  // arities: per predicate, the number of arguments (home excluded).
  explicit Mailboxes(std::vector<std::uint32_t> arities);
  ~Mailboxes();
  Mailboxes(const Mailboxes&) = delete;
  Mailboxes& operator=(const Mailboxes&) = delete;

  void addNodes(NodeId count) { boxes_.resize(boxes_.size() + count); }
  // Appends a message; the arguments are stored as given (the caller owns their references, which
  // pass to whoever takes the message in).
  void post(NodeId dest, PredId p, bool negative, const Value* args) {
    const std::uint32_t arity = arity_[p];
    Box& b = boxes_[dest];
    std::uint32_t c = b.last;
    if (c == kNone || used(c) + 1 + arity > chunkWords_ - 1) {
      const std::uint32_t fresh = newChunk();
      if (c == kNone)
        b.first = fresh;
      else
        chunk(c)[0] = Value::fromBits((chunk(c)[0].bits() & 0xFFFFFFFF00000000ull) | fresh);
      b.last = c = fresh;
    }
    Value* head = chunk(c);
    const std::uint64_t at = head[0].bits() >> 32;
    Value* r = head + 1 + at;
    r[0] = Value::fromBits(std::uint64_t(p) | (std::uint64_t(negative) << 32));
    for (std::uint32_t i = 0; i < arity; ++i) r[1 + i] = args[i];
    head[0] = Value::fromBits((head[0].bits() & 0xFFFFFFFFull) | ((at + 1 + arity) << 32));
  }
  bool empty(NodeId n) const { return boxes_[n].first == kNone; }

  // Calls f(pred, negative, args) for every message of node n in arrival order, leaving them in
  // the box (release() empties it). f must not post to n.
  template <class F>
  void forEach(NodeId n, F&& f) const {
    for (std::uint32_t c = boxes_[n].first; c != kNone;) {
      const Value* head = chunk(c);
      const std::uint32_t next = std::uint32_t(head[0].bits());
      if (next != kNone) prefetchChunk(next);
      forEachRecord(head, f);
      c = next;
    }
  }
  // Empties node n's box; the messages' references must have been taken over or released.
  void release(NodeId n) {
    std::uint32_t c = boxes_[n].first;
    boxes_[n] = Box{};
    while (c != kNone) {
      const std::uint32_t next = std::uint32_t(chunk(c)[0].bits());
      chunk(c)[0] = Value::fromBits(free_);
      free_ = c;
      c = next;
    }
  }
  // Every message still waiting, in no particular order (to release references at the end).
  template <class F>
  void forEachPending(F&& f) const {
    for (const Box& b : boxes_)
      for (std::uint32_t c = b.first; c != kNone; c = std::uint32_t(chunk(c)[0].bits()))
        forEachRecord(chunk(c), [&](PredId p, bool, const Value* args) { f(p, args); });
  }

  // Prefetch hints for a node that runs soon (always inlined: GCC drops calls to functions whose
  // only effect is a prefetch).
  [[gnu::always_inline]] void prefetchBox(NodeId n) const { __builtin_prefetch(&boxes_[n]); }
  [[gnu::always_inline]] void prefetchMessages(NodeId n) const {
    if (boxes_[n].first != kNone) prefetchChunk(boxes_[n].first);
  }
  [[gnu::always_inline]] void prefetchTail(NodeId n) const {
    if (boxes_[n].last != kNone) __builtin_prefetch(chunk(boxes_[n].last));
  }
  std::size_t bytesReserved() const {
    std::size_t chunks = 0;
    for (std::size_t s = 0; s < slabs_.size(); ++s) chunks += slabCapacity(s);
    return chunks * chunkWords_ * sizeof(Value) + boxes_.capacity() * sizeof(Box);
  }

 private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  // Chunk ids are [slab | chunk in slab]. Slabs hold up to kSlabChunks chunks (2 MiB); the first
  // two are smaller, so that a small program or robot world keeps a small footprint.
  static constexpr std::uint32_t kSlabShift = 13, kSlabChunks = 1u << kSlabShift;
  static std::uint32_t slabCapacity(std::size_t slab) {
    return slab == 0 ? 16 : slab == 1 ? 1024 : kSlabChunks;
  }
  struct Box {
    std::uint32_t first = kNone, last = kNone;
  };
  // A chunk: [next | words used] then records of [pred | negative] + the predicate's arguments.
  Value* chunk(std::uint32_t c) const {
    return slabs_[c >> kSlabShift] + std::size_t(c & (kSlabChunks - 1)) * chunkWords_;
  }
  std::uint32_t used(std::uint32_t c) const { return std::uint32_t(chunk(c)[0].bits() >> 32); }
  [[gnu::always_inline]] void prefetchChunk(std::uint32_t c) const {
    const char* p = reinterpret_cast<const char*>(chunk(c));
    for (std::size_t off = 0; off < chunkWords_ * sizeof(Value); off += 64) __builtin_prefetch(p + off);
  }
  template <class F>
  void forEachRecord(const Value* head, F&& f) const {
    const std::uint32_t end = 1 + std::uint32_t(head[0].bits() >> 32);
    for (std::uint32_t w = 1; w < end;) {
      const Value* r = head + w;
      const PredId p = PredId(r[0].bits());
      f(p, (r[0].bits() >> 32) != 0, r + 1);
      w += 1 + arity_[p];
    }
  }
  std::uint32_t newChunk();

  std::vector<std::uint32_t> arity_;
  std::uint32_t chunkWords_;
  std::vector<Value*> slabs_;   // from LargeAllocator, freed by the destructor
  std::uint32_t slabUsed_ = 0;  // chunks handed out of the last slab
  std::uint32_t free_ = kNone;
  std::vector<Box> boxes_;
};

}  // namespace meldvm
