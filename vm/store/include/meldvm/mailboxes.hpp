// Facts in transit to nodes (spec §6.6): per node, the messages not yet taken in, in arrival
// order. A node's messages live in chains of fixed-size chunks (256 bytes), so taking in a run's
// worth of messages touches a few cache lines in a row instead of one scattered record per
// message. A record takes only the words its own predicate needs, so small facts pack densely: a
// wide flood keeps millions of messages in flight, and every word of them is written and read
// back from memory. Chunks come from slabs that never move (growing copies nothing) and are
// recycled through a free list, so the steady state allocates nothing (the shards of a threaded
// run share their chunks: mail_slabs.hpp).
//
// Record layout, in 8-byte words. The first word holds the predicate (low 31 bits) and the sign
// (bit 31) in its low half. A predicate whose arguments are all 32-bit scalars (int, bool, node,
// thread) is "narrow": its arguments take 4 bytes each, the first one in the high half of the first
// word, the others two to a word after it (so `p(node, min int)` takes one word, not two). Other
// predicates keep one word per argument after the first word.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "meldvm/large_allocator.hpp"
#include "meldvm/mail_slabs.hpp"
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
  // shapes: per predicate, the widths of its arguments (home excluded). shared: the chunk table of
  // the run's shards, this one being shard `self` (nullptr: a table of its own).
  explicit Mailboxes(const std::vector<std::vector<ArgWidth>>& shapes, MailSlabs* shared = nullptr,
                     std::uint32_t self = 0);
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

  // A node's waiting messages as they stand, for another shard's mailboxes of the same MailSlabs.
  struct Chain {
    std::uint32_t first = kNone, last = kNone;
    std::uint32_t used = 0;  // words of records in the last chunk
    bool empty() const { return first == kNone; }
  };
  // Node n's messages leave its box, which is left empty; the chunks and the messages' references
  // go with the chain.
  Chain detach(NodeId n) {
    const Chain c = boxes_[n];
    boxes_[n] = Chain{};
    return c;
  }
  // The chain's messages join node n's box, after those already there.
  void attach(NodeId n, const Chain& c) {
    if (c.first == kNone) return;
    Chain& b = boxes_[n];
    if (b.first == kNone) {
      b = c;
      return;
    }
    chunk(b.last)[0] = Value::fromBits(c.first | (std::uint64_t(b.used) << 32));  // closed: link and length
    b.last = c.last;
    b.used = c.used;
  }

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
    // A shard with plenty of free chunks gives the box's to the run's spares (chunks that moved
    // here with nodes would otherwise pile up here while the giver maps new slabs).
    const bool spare = spares_ && freeChunks_ >= kKeptFreeChunks;
    std::uint32_t c = boxes_[n].first, head = spare ? kNone : free_, tail = kNone, chunks = 0;
    for (; c != kNone && chunks < maxChunks; ++chunks) {
      const std::uint32_t next = std::uint32_t(chunk(c)[0].bits());
      chunk(c)[0] = Value::fromBits(head);
      if (tail == kNone) tail = c;
      head = c;
      c = next;
    }
    if (spare) {
      if (chunks) giveSpares(head, tail, chunks);
    } else {
      free_ = head;
      freeChunks_ += chunks;
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
  // The slabs this one allocated (chunks move between the shards' mailboxes; slabs do not).
  std::size_t bytesReserved() const {
    std::size_t chunks = 0;
    for (std::uint32_t s = 0; s < slabCount_; ++s) chunks += slabCapacity(s);
    return chunks * chunkWords_ * sizeof(Value) + boxes_.capacity() * sizeof(Box);
  }

 private:
  static constexpr std::uint32_t kNone = MailSlabs::kNoChunk;
  // Chunk ids are [slab | chunk in slab] (MailSlabs). Slabs hold up to kSlabChunks chunks (2 MiB);
  // a shard's first four are smaller, so that a small program or robot world keeps a small
  // footprint: a slab of 2 MiB gets huge pages (LargeAllocator), all of it resident at its first
  // message, and on belief-propagation-50 at -j 2 the two shards' first such slabs were 4 MB of
  // 14 (serially 8.4). The next two (1 MiB each) get small pages, resident as they fill.
  static constexpr std::uint32_t kSlabShift = MailSlabs::kChunkBits, kSlabChunks = 1u << kSlabShift;
  static std::uint32_t slabCapacity(std::uint32_t ownSlab) {
    return ownSlab == 0 ? 16 : ownSlab == 1 ? 1024 : ownSlab < 4 ? kSlabChunks / 2 : kSlabChunks;
  }
  // The last chunk's length is kept here, not in the chunk: a post then writes its record without
  // first reading the chunk (a cache miss per message on a large graph). A chunk's head gets its
  // final length when the next chunk is linked.
  using Box = Chain;
  struct Shape {
    std::uint32_t arity;
    std::uint32_t words;     // the record's length
    std::uint32_t signMask;  // narrow: bit i set when argument i is an int (sign-extended)
    bool narrow;
  };
  static constexpr std::uint32_t kMaxNarrowArity = 16;  // wider predicates keep whole words
  // A chunk: [next | words used (once closed)] then the records.
  Value* chunk(std::uint32_t c) const {
    return table_[c >> kSlabShift] + std::size_t(c & (kSlabChunks - 1)) * chunkWords_;
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
  // The run's spare chunks (MailSlabs): a chain of `chunks` free chunks, head to tail, joins them;
  // takeSpares moves them all to this one's free list (false: there were none).
  void giveSpares(std::uint32_t head, std::uint32_t tail, std::uint32_t chunks);
  bool takeSpares();
  static constexpr std::uint32_t kKeptFreeChunks = 1024;  // 256 KiB

  std::vector<Shape> shape_;
  std::uint32_t chunkWords_;
  std::unique_ptr<MailSlabs> ownSlabs_;  // a serial machine's
  MailSlabs::Spares* spares_ = nullptr;  // a shard's: the run's
  Value** table_;                        // the MailSlabs' table
  std::uint32_t firstSlab_, endSlab_;    // this one's range of it
  std::uint32_t slabCount_ = 0;          // slabs allocated (LargeAllocator), freed by the destructor
  std::uint32_t slabUsed_ = 0;           // chunks handed out of the last slab
  std::uint32_t free_ = kNone;
  std::uint32_t freeChunks_ = 0;  // on free_
  std::vector<Box> boxes_;
};

}  // namespace meldvm
