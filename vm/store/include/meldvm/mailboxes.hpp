// Facts in transit to nodes (spec §6.6): per node, the messages not yet taken in, in arrival
// order. A node's messages live in chains of fixed-size chunks (256 bytes), so taking in a run's
// worth of messages touches a few cache lines in a row instead of one scattered record per
// message. A record takes only the words its own predicate needs, so small facts pack densely: a
// wide flood keeps millions of messages in flight, and every word of them is written and read
// back from memory. Chunks come from slabs that never move (growing copies nothing) and are
// recycled through a free list, so the steady state allocates nothing.
//
// Record layout, in 8-byte words. The first word holds the predicate (low 31 bits) and the sign
// (bit 31) in its low half. A predicate whose arguments are all 32-bit scalars (int, bool, node,
// thread) is "narrow": its arguments take 4 bytes each, the first one in the high half of the first
// word, the others two to a word after it (so `p(node, min int)` takes one word, not two). Other
// predicates keep one word per argument after the first word.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/large_allocator.hpp"
#include "meldvm/predicate.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

// How a message keeps one argument: a whole word, or the low 4 bytes of an int (sign-extended when
// read back) or of a bool, node or thread id (zero-extended).
enum class ArgWidth : std::uint8_t { Word, Int32, Uint32 };
inline ArgWidth argWidth(TypeKind k) {
  if (k == TypeKind::Int) return ArgWidth::Int32;
  if (k == TypeKind::Bool || k == TypeKind::Node || k == TypeKind::Thread) return ArgWidth::Uint32;
  return ArgWidth::Word;
}

class Mailboxes {
 public:
  // shapes: per predicate, the widths of its arguments (home excluded).
  explicit Mailboxes(const std::vector<std::vector<ArgWidth>>& shapes);
  ~Mailboxes();
  Mailboxes(const Mailboxes&) = delete;
  Mailboxes& operator=(const Mailboxes&) = delete;

  void addNodes(NodeId count) { boxes_.resize(boxes_.size() + count); }
  // Appends a message; the arguments are stored as given (the caller owns their references, which
  // pass to whoever takes the message in).
  void post(NodeId dest, PredId p, bool negative, const Value* args) {
    const Shape& s = shape_[p];
    Box& b = boxes_[dest];
    std::uint32_t c = b.last;
    if (c == kNone || b.used + s.words > chunkWords_ - 1) {
      const std::uint32_t fresh = newChunk();
      if (c == kNone)
        b.first = fresh;
      else
        chunk(c)[0] = Value::fromBits(fresh | (std::uint64_t(b.used) << 32));  // closed: link and length
      b.last = c = fresh;
      b.used = 0;
    }
    Value* r = chunk(c) + 1 + b.used;
    b.used += s.words;
    const std::uint64_t tag = std::uint64_t(p) | (std::uint64_t(negative) << 31);
    if (s.narrow) {
      r[0] = Value::fromBits(tag | (s.arity ? args[0].bits() << 32 : 0));
      for (std::uint32_t i = 1; i < s.arity; ++i) {
        Value& w = r[1 + (i - 1) / 2];
        w = Value::fromBits(i % 2 ? std::uint32_t(args[i].bits()) : w.bits() | args[i].bits() << 32);
      }
    } else {
      r[0] = Value::fromBits(tag);
      for (std::uint32_t i = 0; i < s.arity; ++i) r[1 + i] = args[i];
    }
  }
  bool empty(NodeId n) const { return boxes_[n].first == kNone; }

  static constexpr std::uint32_t kAllChunks = 0xFFFFFFFFu;  // forEach / release: the whole box
  // Calls f(pred, negative, args) for every message of node n whose predicate passes select(pred),
  // in arrival order, leaving them in the box (release() empties it). f must not post to n. With
  // maxChunks, only the messages of the box's first chunks (the earliest arrivals).
  template <class Select, class F>
  void forEach(NodeId n, Select&& select, F&& f, std::uint32_t maxChunks = kAllChunks) const {
    const Box& b = boxes_[n];
    std::uint32_t chunks = 0;
    for (std::uint32_t c = b.first; c != kNone && chunks++ < maxChunks;) {
      const Value* head = chunk(c);
      const std::uint32_t next = std::uint32_t(head[0].bits());
      if (next != kNone) prefetchChunk(next);
      forEachRecord(head, wordsUsed(b, c), select, f);
      c = next;
    }
  }
  // Empties node n's box, or its first maxChunks chunks; the messages' references must have been
  // taken over or released.
  void release(NodeId n, std::uint32_t maxChunks = kAllChunks) {
    std::uint32_t c = boxes_[n].first;
    for (std::uint32_t chunks = 0; c != kNone && chunks < maxChunks; ++chunks) {
      const std::uint32_t next = std::uint32_t(chunk(c)[0].bits());
      chunk(c)[0] = Value::fromBits(free_);
      free_ = c;
      c = next;
    }
    if (c == kNone)
      boxes_[n] = Box{};
    else
      boxes_[n].first = c;
  }
  // Every message still waiting, in no particular order (to release references at the end).
  template <class F>
  void forEachPending(F&& f) const {
    for (const Box& b : boxes_)
      for (std::uint32_t c = b.first; c != kNone; c = std::uint32_t(chunk(c)[0].bits()))
        forEachRecord(
            chunk(c), wordsUsed(b, c), [](PredId) { return true; },
            [&](PredId p, bool, const Value* args) { f(p, args); });
  }

  // Prefetch hints for a node that runs soon (always inlined: GCC drops calls to functions whose
  // only effect is a prefetch).
  [[gnu::always_inline]] void prefetchBox(NodeId n) const { __builtin_prefetch(&boxes_[n]); }
  [[gnu::always_inline]] void prefetchMessages(NodeId n) const {
    if (boxes_[n].first != kNone) prefetchChunk(boxes_[n].first);
  }
  [[gnu::always_inline]] void prefetchTail(NodeId n) const {
    const Box& b = boxes_[n];
    if (b.last != kNone) __builtin_prefetch(chunk(b.last) + 1 + b.used, 1);
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
  // The last chunk's length is kept here, not in the chunk: a post then writes its record without
  // first reading the chunk (a cache miss per message on a large graph). A chunk's head gets its
  // final length when the next chunk is linked.
  struct Box {
    std::uint32_t first = kNone, last = kNone;
    std::uint32_t used = 0;  // words of records in the last chunk
  };
  struct Shape {
    std::uint32_t arity;
    std::uint32_t words;     // the record's length
    std::uint32_t signMask;  // narrow: bit i set when argument i is an int (sign-extended)
    bool narrow;
  };
  static constexpr std::uint32_t kMaxNarrowArity = 16;  // wider predicates keep whole words
  // A chunk: [next | words used (once closed)] then the records.
  Value* chunk(std::uint32_t c) const {
    return slabs_[c >> kSlabShift] + std::size_t(c & (kSlabChunks - 1)) * chunkWords_;
  }
  std::uint32_t wordsUsed(const Box& b, std::uint32_t c) const {
    return c == b.last ? b.used : std::uint32_t(chunk(c)[0].bits() >> 32);
  }
  [[gnu::always_inline]] void prefetchChunk(std::uint32_t c) const {
    const char* p = reinterpret_cast<const char*>(chunk(c));
    for (std::size_t off = 0; off < chunkWords_ * sizeof(Value); off += 64) __builtin_prefetch(p + off);
  }
  static Value widen(std::uint32_t half, bool isSigned) {
    return isSigned ? Value::fromInt(std::int32_t(half)) : Value::fromBits(half);
  }
  template <class Select, class F>
  void forEachRecord(const Value* head, std::uint32_t used, Select&& select, F&& f) const {
    const std::uint32_t end = 1 + used;
    Value args[kMaxNarrowArity];
    for (std::uint32_t w = 1; w < end;) {
      const Value* r = head + w;
      const std::uint64_t tag = r[0].bits();
      const PredId p = PredId(tag & 0x7FFFFFFFu);
      const Shape& s = shape_[p];
      w += s.words;
      if (!select(p)) continue;
      const bool negative = (tag >> 31) & 1;
      if (s.narrow) {
        if (s.arity) args[0] = widen(std::uint32_t(tag >> 32), s.signMask & 1);
        for (std::uint32_t i = 1; i < s.arity; ++i) {
          const std::uint64_t word = r[1 + (i - 1) / 2].bits();
          args[i] = widen(std::uint32_t(i % 2 ? word : word >> 32), (s.signMask >> i) & 1);
        }
        f(p, negative, static_cast<const Value*>(args));
      } else {
        f(p, negative, r + 1);
      }
    }
  }
  std::uint32_t newChunk();

  std::vector<Shape> shape_;
  std::uint32_t chunkWords_;
  std::vector<Value*> slabs_;   // from LargeAllocator, freed by the destructor
  std::uint32_t slabUsed_ = 0;  // chunks handed out of the last slab
  std::uint32_t free_ = kNone;
  std::vector<Box> boxes_;
};

}  // namespace meldvm
