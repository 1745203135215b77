// Facts in transit to nodes (spec §6.6): per node, the messages not yet taken in, in arrival
// order. A node's messages live in chains of chunks, so taking in a run's worth of messages
// touches a few cache lines in a row instead of one scattered record per message. Chunks are
// small (128 bytes) or big (256 bytes): at -j 2 nearly every node of a grid or a graph has a few
// messages waiting at any time (one chunk a node: 256-byte chunks were 2.6 of heat-transfer's 6
// MB above the serial run's), while a node that takes in thousands at once (n-queens) gets them
// in big chunks (128-byte ones throughout made it 7-12 % slower). A box starts with a small chunk
// unless its last messages overflowed one (a pagerank node's eight: two chunks a run instead of
// one cost 4 % at -j 2); the chunks after the first are big. A record takes only the words its
// own predicate needs, so small facts pack densely: a wide flood keeps millions of messages in
// flight, and every word of them is written and read back from memory. Chunks come from slabs
// that never move (growing copies nothing) and are recycled through free lists, so the steady
// state allocates nothing (the shards of a threaded run share their chunks: mail_slabs.hpp).
//
// Record layout, in 8-byte words. The first word holds the predicate (low 31 bits) and the sign
// (bit 31) in its low half. A predicate whose arguments are all 32-bit scalars (int, bool, node,
// thread) is "narrow": its arguments take 4 bytes each, the first one in the high half of the first
// word, the others two to a word after it (so `p(node, min int)` takes one word, not two). One
// with both kinds is "mixed": its 32-bit arguments take the free halves in that order, its other
// arguments a word each (so `p(node, float)` takes two words, not three: a grid's or a graph's
// messages in flight, one chunk a node at -j 2, fit in half the chunks). Predicates of 32-bit-wide
// arguments only or of more than 16 arguments keep one word per argument after the first word.
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
    if (c == kNone || b.words() + s.words > capacity(b.lastIsBig()) - 1) {
      const bool big = c != kNone || (b.used & Chain::kStartBig);
      const std::uint32_t fresh = newChunk(big);
      if (c == kNone)
        b.first = fresh;
      else
        close(c, b, fresh);
      b.last = c = fresh;
      b.used = big ? Chain::kLastIsBig : 0;
    }
    Value* r = chunk(c) + 1 + b.words();
    b.used += s.words;
    const std::uint64_t tag = std::uint64_t(p) | (std::uint64_t(negative) << 31);
    if (s.layout == Layout::Narrow) {
      r[0] = Value::fromBits(tag | (s.arity ? args[0].bits() << 32 : 0));
      for (std::uint32_t i = 1; i < s.arity; ++i) {
        Value& w = r[1 + (i - 1) / 2];
        w = Value::fromBits(i % 2 ? std::uint32_t(args[i].bits()) : w.bits() | args[i].bits() << 32);
      }
    } else if (s.layout == Layout::Mixed) {
      writeMixed(r, s, tag, args);
    } else {
      r[0] = Value::fromBits(tag);
      for (std::uint32_t i = 0; i < s.arity; ++i) r[1 + i] = args[i];
    }
  }
  bool empty(NodeId n) const { return boxes_[n].first == kNone; }

  // A node's waiting messages as they stand, for another shard's mailboxes of the same MailSlabs.
  struct Chain {
    // kStartBig: an empty box's next chain starts with a big chunk (its last one outgrew a small one).
    static constexpr std::uint32_t kLastIsBig = 0x80000000u, kStartBig = 0x40000000u;
    std::uint32_t first = kNone, last = kNone;
    std::uint32_t used = 0;  // words of records in the last chunk, and the flags
    bool empty() const { return first == kNone; }
    std::uint32_t words() const { return used & ~(kLastIsBig | kStartBig); }
    bool lastIsBig() const { return used & kLastIsBig; }
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
    close(b.last, b, c.first);
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
      if (next != kNone) prefetchChunk(next, true);  // (a box's chunks after the first are big)
      forEachRecord(head, wordsUsed(b, c), select, f);
      c = next;
    }
  }
  // Empties node n's box, or its first maxChunks chunks; the messages' references must have been
  // taken over or released.
  void release(NodeId n, std::uint32_t maxChunks = kAllChunks) {
    if (boxes_[n].first == kNone) return;  // (every node run of the serial VM asks)
    // A shard with plenty of free chunks gives the box's to the run's spares (chunks that moved
    // here with nodes would otherwise pile up here while the giver maps new slabs).
    const bool spare[2] = {spares_ && free_.of[0].chunks >= kKeptFreeCells,
                           spares_ && free_.of[1].chunks * 2 >= kKeptFreeCells};
    FreeChains freed;
    const Box b = boxes_[n];
    std::uint32_t c = b.first;
    for (std::uint32_t chunks = 0; c != kNone && chunks < maxChunks; ++chunks) {
      const std::uint64_t header = chunk(c)[0].bits();
      const bool big = header & kBigBit;
      push(spare[big] ? freed : free_, c, big);
      c = std::uint32_t(header);
    }
    if (spare[0] || spare[1]) giveSpares(freed);
    if (c == kNone)
      boxes_[n] = Box{kNone, kNone, b.first != b.last || b.words() >= cellWords_ ? Chain::kStartBig : 0};
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
    if (boxes_[n].first != kNone) prefetchChunk(boxes_[n].first, false);
  }
  [[gnu::always_inline]] void prefetchTail(NodeId n) const {
    const Box& b = boxes_[n];
    if (b.last != kNone) __builtin_prefetch(chunk(b.last) + 1 + b.words(), 1);
  }
  // The slabs this one allocated (chunks move between the shards' mailboxes; slabs do not).
  std::size_t bytesReserved() const {
    std::size_t cells = 0;
    for (std::uint32_t s = 0; s < slabCount_; ++s) cells += slabCapacity(s);
    return cells * cellWords_ * sizeof(Value) + boxes_.capacity() * sizeof(Box);
  }

 private:
  static constexpr std::uint32_t kNone = MailSlabs::kNoChunk;
  // Chunks are made of cells (cellWords_ words: 128 bytes, or one record of the widest predicate
  // when that is larger); a small chunk is one cell, a big one two cells in a row. Chunk ids are
  // the id of their first cell, [slab | cell in slab] (MailSlabs). A shard's first two slabs are
  // small, so that a small program or robot world keeps a small footprint; the others hold up to
  // kSlabCells / 2 cells (1 MiB), which get small pages, resident as they fill (2 MiB slabs got
  // huge pages, all of a slab resident at its first message: on pagerank at -j 2 each shard's last
  // slab was a sixth used, 3.2 MB of the run's 44.5).
  static constexpr std::uint32_t kSlabShift = MailSlabs::kCellBits, kSlabCells = 1u << kSlabShift;
  static std::uint32_t slabCapacity(std::uint32_t ownSlab) {
    return ownSlab == 0 ? 32 : ownSlab == 1 ? 2048 : kSlabCells / 2;
  }
  std::uint32_t capacity(bool big) const { return big ? 2 * cellWords_ : cellWords_; }
  // The last chunk's length and size are kept here, not in the chunk: a post then writes its record
  // without first reading the chunk (a cache miss per message on a large graph). A chunk's head
  // gets its final length when the next chunk is linked.
  using Box = Chain;
  enum class Layout : std::uint8_t { Narrow, Mixed, Whole };
  struct Shape {
    std::uint32_t arity;
    std::uint32_t words;       // the record's length
    std::uint32_t signMask;    // narrow: bit i set when argument i is an int (sign-extended)
    std::uint32_t firstPlace;  // mixed: the arguments' places start at places_[firstPlace]
    Layout layout;
  };
  // Where a mixed record keeps an argument: the 4-byte half of the record it starts at (half 1 is
  // the first word's high half), and its width.
  struct Place {
    std::uint16_t half;
    ArgWidth width;
  };
  static constexpr std::uint32_t kMaxNarrowArity = 16;  // wider predicates keep whole words
  static Shape shapeOf(const std::vector<ArgWidth>& fields, std::vector<Place>& places);
  // A mixed record written and read back (out of line: inlined in every caller of post and
  // forEach, they made the serial VM's hot functions larger, and heat-transfer 5 % slower, for
  // records it rarely sees).
  [[gnu::noinline]] void writeMixed(Value* r, const Shape& s, std::uint64_t tag, const Value* args) const;
  [[gnu::noinline]] void readMixed(const Value* r, const Shape& s, Value* args) const;
  // A chunk: [next (low half) | words used (once closed) | big (the top bit)] then the records.
  Value* chunk(std::uint32_t c) const {
    return table_[c >> kSlabShift] + std::size_t(c & (kSlabCells - 1)) * cellWords_;
  }
  static constexpr std::uint64_t kBigBit = std::uint64_t(1) << 63;
  std::uint32_t wordsUsed(const Box& b, std::uint32_t c) const {
    return c == b.last ? b.words() : std::uint32_t((chunk(c)[0].bits() & ~kBigBit) >> 32);
  }
  // Chunk c, the last of box b, is full: `next` follows it.
  void close(std::uint32_t c, const Box& b, std::uint32_t next) {
    chunk(c)[0] = Value::fromBits(next | std::uint64_t(b.words()) << 32 | (b.lastIsBig() ? kBigBit : 0));
  }
  [[gnu::always_inline]] void prefetchChunk(std::uint32_t c, bool big) const {
    const char* p = reinterpret_cast<const char*>(chunk(c));
    for (std::size_t off = 0; off < capacity(big) * sizeof(Value); off += 64) __builtin_prefetch(p + off);
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
      if (s.layout == Layout::Narrow) {
        if (s.arity) args[0] = widen(std::uint32_t(tag >> 32), s.signMask & 1);
        for (std::uint32_t i = 1; i < s.arity; ++i) {
          const std::uint64_t word = r[1 + (i - 1) / 2].bits();
          args[i] = widen(std::uint32_t(i % 2 ? word : word >> 32), (s.signMask >> i) & 1);
        }
        f(p, negative, static_cast<const Value*>(args));
      } else if (s.layout == Layout::Mixed) {
        readMixed(r, s, args);
        f(p, negative, static_cast<const Value*>(args));
      } else {
        f(p, negative, r + 1);
      }
    }
  }
  std::uint32_t newChunk(bool big);
  std::uint32_t freshCells(std::uint32_t cells);  // from the last slab, or a new one

  // Free chunks, small and big: chains through their first words.
  using FreeChain = MailSlabs::FreeChain;
  struct FreeChains {
    FreeChain of[2];  // [big]
  };
  void push(FreeChains& chains, std::uint32_t c, bool big) {
    FreeChain& f = chains.of[big];
    chunk(c)[0] = Value::fromBits(f.head);
    if (f.tail == kNone) f.tail = c;
    f.head = c;
    ++f.chunks;
  }
  void splice(FreeChain& into, FreeChain& from) {  // from's chunks go before into's
    if (from.head == kNone) return;
    chunk(from.tail)[0] = Value::fromBits(into.head);
    if (into.tail == kNone) into.tail = from.tail;
    into.head = from.head;
    into.chunks += from.chunks;
    from = FreeChain{};
  }
  // The run's spare chunks (MailSlabs): giveSpares adds chains to them; takeSpares moves all those
  // of one size to this one's free list (false: there were none). Each size apart: a shard that
  // took both kept the small ones it did not need while the other one mapped new slabs for them
  // (pagerank at -j 2: 520,000 free small chunks on one side, 250,000 big ones on the other).
  void giveSpares(FreeChains& chains);
  bool takeSpares(bool big);
  static constexpr std::uint32_t kKeptFreeCells = 2048;  // 256 KiB

  std::vector<Shape> shape_;
  std::vector<Place> places_;
  std::uint32_t cellWords_;
  std::unique_ptr<MailSlabs> ownSlabs_;  // a serial machine's
  MailSlabs::Spares* spares_ = nullptr;  // a shard's: the run's
  Value** table_;                        // the MailSlabs' table
  std::uint32_t firstSlab_, endSlab_;    // this one's range of it
  std::uint32_t slabCount_ = 0;          // slabs allocated (LargeAllocator), freed by the destructor
  std::uint32_t slabUsed_ = 0;           // cells handed out of the last slab
  FreeChains free_;
  std::vector<Box> boxes_;
};

}  // namespace meldvm
