// Facts in transit to nodes (spec §6.6): per node, the messages not yet taken in, in arrival
// order. A node's messages live in chains of fixed-size chunks (about 256 bytes), so taking in a
// run's worth of messages touches a few cache lines in a row instead of one scattered record per
// message; chunks are recycled through a free list, so the steady state allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/predicate.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

class Mailboxes {
 public:
  explicit Mailboxes(std::uint32_t maxArity);

  void addNodes(NodeId count) { boxes_.resize(boxes_.size() + count); }
  // Appends a message; the arguments are stored as given (the caller owns their references, which
  // pass to whoever drains the message).
  void post(NodeId dest, PredId p, bool negative, const Value* args, std::uint32_t arity) {
    Box& b = boxes_[dest];
    std::uint32_t c = b.last;
    if (c == kNone || (words_[std::size_t(c) * chunkWords_].bits() >> 32) == perChunk_) {
      const std::uint32_t fresh = newChunk();
      if (c == kNone)
        b.first = fresh;
      else
        words_[std::size_t(c) * chunkWords_] =
            Value::fromBits((words_[std::size_t(c) * chunkWords_].bits() & 0xFFFFFFFF00000000ull) | fresh);
      b.last = c = fresh;
    }
    Value& head = words_[std::size_t(c) * chunkWords_];
    const std::uint64_t count = head.bits() >> 32;
    Value* r = words_.data() + std::size_t(c) * chunkWords_ + 1 + count * recordWords_;
    r[0] = Value::fromBits(std::uint64_t(p) | (std::uint64_t(negative) << 32));
    for (std::uint32_t i = 0; i < arity; ++i) r[1 + i] = args[i];
    head = Value::fromBits((head.bits() & 0xFFFFFFFFull) | ((count + 1) << 32));
  }
  bool empty(NodeId n) const { return boxes_[n].first == kNone; }

  // Calls f(pred, negative, args) for every message of node n in arrival order, leaving them in
  // the box (release() empties it). f must not post to n.
  template <class F>
  void forEach(NodeId n, F&& f) const {
    for (std::uint32_t c = boxes_[n].first; c != kNone;) {
      const Value* chunk = words_.data() + std::size_t(c) * chunkWords_;
      const std::uint32_t next = std::uint32_t(chunk[0].bits()), count = std::uint32_t(chunk[0].bits() >> 32);
      if (next != kNone) {
        const char* p = reinterpret_cast<const char*>(words_.data() + std::size_t(next) * chunkWords_);
        for (std::size_t off = 0; off < chunkWords_ * sizeof(Value); off += 64) __builtin_prefetch(p + off);
      }
      for (std::uint32_t i = 0; i < count; ++i) {
        const Value* r = chunk + 1 + std::size_t(i) * recordWords_;
        f(PredId(r[0].bits()), (r[0].bits() >> 32) != 0, r + 1);
      }
      c = next;
    }
  }
  // Empties node n's box; the messages' references must have been taken over or released.
  void release(NodeId n) {
    std::uint32_t c = boxes_[n].first;
    boxes_[n] = Box{};
    while (c != kNone) {
      const std::uint32_t next = std::uint32_t(words_[std::size_t(c) * chunkWords_].bits());
      words_[std::size_t(c) * chunkWords_] = Value::fromBits(free_);
      free_ = c;
      c = next;
    }
  }
  // Every message still waiting, in no particular order (to release references at the end).
  template <class F>
  void forEachPending(F&& f) const {
    for (const Box& b : boxes_)
      for (std::uint32_t c = b.first; c != kNone;) {
        const Value* chunk = words_.data() + std::size_t(c) * chunkWords_;
        const std::uint32_t count = std::uint32_t(chunk[0].bits() >> 32);
        for (std::uint32_t i = 0; i < count; ++i) {
          const Value* r = chunk + 1 + std::size_t(i) * recordWords_;
          f(PredId(r[0].bits()), r + 1);
        }
        c = std::uint32_t(chunk[0].bits());
      }
  }

  // Prefetch hints for a node that runs soon (always inlined: GCC drops calls to functions whose
  // only effect is a prefetch).
  [[gnu::always_inline]] void prefetchBox(NodeId n) const { __builtin_prefetch(&boxes_[n]); }
  [[gnu::always_inline]] void prefetchMessages(NodeId n) const {
    const std::uint32_t c = boxes_[n].first;
    if (c == kNone) return;
    const char* p = reinterpret_cast<const char*>(words_.data() + std::size_t(c) * chunkWords_);
    for (std::size_t off = 0; off < chunkWords_ * sizeof(Value); off += 64) __builtin_prefetch(p + off);
  }
  [[gnu::always_inline]] void prefetchTail(NodeId n) const {
    const std::uint32_t c = boxes_[n].last;
    if (c != kNone) __builtin_prefetch(words_.data() + std::size_t(c) * chunkWords_);
  }
  std::size_t bytesReserved() const {
    return words_.capacity() * sizeof(Value) + boxes_.capacity() * sizeof(Box);
  }

 private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  struct Box {
    std::uint32_t first = kNone, last = kNone;
  };
  std::uint32_t newChunk();

  std::uint32_t recordWords_, perChunk_, chunkWords_;
  std::vector<Value> words_;  // chunks: [next | count] then perChunk_ records of [pred | negative] + args
  std::uint32_t free_ = kNone;
  std::vector<Box> boxes_;
};

}  // namespace meldvm
