#include "meldvm/mailboxes.hpp"

#include <algorithm>
#include <stdexcept>

namespace meldvm {

Mailboxes::Mailboxes(const std::vector<std::vector<ArgWidth>>& shapes, MailSlabs* shared,
                     std::uint32_t self) {
  if (!shared) {
    ownSlabs_ = std::make_unique<MailSlabs>(1);
    shared = ownSlabs_.get();
    self = 0;
  } else {
    spares_ = &shared->spares();
  }
  table_ = shared->table();
  firstSlab_ = shared->firstSlab(self);
  endSlab_ = firstSlab_ + shared->slabsPerShard();
  if (shapes.size() > 0x80000000u) throw std::length_error("meldvm: too many predicates for the mailboxes");
  std::uint32_t widest = 0;
  for (const std::vector<ArgWidth>& fields : shapes) {
    shape_.push_back(shapeOf(fields, places_));
    widest = std::max(widest, shape_.back().words);
  }
  // 16 words (two cache lines), or one record of the widest predicate when that is larger.
  cellWords_ = std::max<std::uint32_t>(16, 1 + widest);
}

Mailboxes::Shape Mailboxes::shapeOf(const std::vector<ArgWidth>& fields, std::vector<Place>& places) {
  const std::uint32_t arity = std::uint32_t(fields.size());
  Shape s{arity, 1 + arity, 0, 0, Layout::Whole};
  const auto words = std::count(fields.begin(), fields.end(), ArgWidth::Word);
  if (arity > kMaxNarrowArity || (words == arity && arity > 0)) return s;
  if (words == 0) {
    s.layout = Layout::Narrow;
    s.words = 1 + arity / 2;
    for (std::uint32_t i = 0; i < arity; ++i)
      if (fields[i] == ArgWidth::Int32) s.signMask |= std::uint32_t(1) << i;
    return s;
  }
  // 4-byte arguments fill the halves in order, a word argument skips to a whole word; the half it
  // skipped (one at most waits) takes the next 4-byte argument.
  s.layout = Layout::Mixed;
  s.firstPlace = std::uint32_t(places.size());
  std::uint16_t next = 1, hole = 0;
  for (const ArgWidth w : fields) {
    if (w != ArgWidth::Word) {
      places.push_back({hole ? hole : next++, w});
      hole = 0;
    } else {
      if (next % 2) {
        if (!hole) hole = next;
        ++next;
      }
      places.push_back({next, w});
      next += 2;
    }
  }
  s.words = (next + 1u) / 2;
  return s;
}

void Mailboxes::writeMixed(Value* r, const Shape& s, std::uint64_t tag, const Value* args) const {
  r[0] = Value::fromBits(tag);
  for (std::uint32_t w = 1; w < s.words; ++w) r[w] = Value::fromBits(0);
  const Place* place = &places_[s.firstPlace];
  for (std::uint32_t i = 0; i < s.arity; ++i) {
    Value& w = r[place[i].half / 2];
    if (place[i].width == ArgWidth::Word)
      w = args[i];
    else
      w = Value::fromBits(w.bits() | std::uint64_t(std::uint32_t(args[i].bits()))
                                         << (place[i].half % 2 * 32));
  }
}

void Mailboxes::readMixed(const Value* r, const Shape& s, Value* args) const {
  const Place* place = &places_[s.firstPlace];
  for (std::uint32_t i = 0; i < s.arity; ++i) {
    const Value w = r[place[i].half / 2];
    args[i] = place[i].width == ArgWidth::Word ? w
                                               : widen(std::uint32_t(w.bits() >> (place[i].half % 2 * 32)),
                                                       place[i].width == ArgWidth::Int32);
  }
}

Mailboxes::~Mailboxes() {
  for (std::uint32_t s = 0; s < slabCount_; ++s)
    LargeAllocator<Value>().deallocate(table_[firstSlab_ + s], std::size_t(slabCapacity(s)) * cellWords_);
}

std::uint32_t Mailboxes::newChunk(bool big) {
  FreeChain& f = free_.of[big];
  std::uint32_t c;
  if (f.head != kNone || (spares_ && takeSpares(big))) {
    c = f.head;
    f.head = std::uint32_t(chunk(c)[0].bits());
    if (f.head == kNone) f.tail = kNone;
    --f.chunks;
  } else {
    c = freshCells(big ? 2 : 1);
  }
  chunk(c)[0] = Value::fromBits(kNone | (big ? kBigBit : 0));  // next = none, no words used
  return c;
}

std::uint32_t Mailboxes::freshCells(std::uint32_t cells) {
  if (slabCount_ == 0 || slabUsed_ + cells > slabCapacity(slabCount_ - 1)) {
    const std::uint32_t slab = firstSlab_ + slabCount_;
    // (The table's last slab is never used: its last cell's id would be kNone.)
    if (slab >= endSlab_ || slab == MailSlabs::kSlabs - 1)
      throw std::length_error("meldvm: too many messages in transit");
    if (slabCount_ && slabUsed_ < slabCapacity(slabCount_ - 1))  // the last cell: a small chunk
      push(free_, ((slab - 1) << kSlabShift) | slabUsed_, false);
    table_[slab] = LargeAllocator<Value>().allocate(std::size_t(slabCapacity(slabCount_)) * cellWords_);
    ++slabCount_;
    slabUsed_ = 0;
  }
  const std::uint32_t slab = firstSlab_ + slabCount_ - 1, c = (slab << kSlabShift) | slabUsed_;
  const std::size_t cellBytes = std::size_t(cellWords_) * sizeof(Value);
  support::prefaultAhead(table_[slab], slabCapacity(slabCount_ - 1) * cellBytes, slabUsed_ * cellBytes,
                         (slabUsed_ + cells) * cellBytes);  // cells are handed out in order
  slabUsed_ += cells;
  return c;
}

void Mailboxes::giveSpares(FreeChains& chains) {
  std::lock_guard<std::mutex> lock(spares_->lock);
  for (int big = 0; big < 2; ++big) {
    if (chains.of[big].head == kNone) continue;
    std::vector<FreeChain>& batches = spares_->batches[big];
    if (batches.empty() || batches.back().chunks >= MailSlabs::kSpareBatchChunks) batches.emplace_back();
    splice(batches.back(), chains.of[big]);
    spares_->any[big].store(true, std::memory_order_relaxed);
  }
}

bool Mailboxes::takeSpares(bool big) {
  if (!spares_->any[big].load(std::memory_order_relaxed)) return false;
  std::lock_guard<std::mutex> lock(spares_->lock);
  std::vector<FreeChain>& batches = spares_->batches[big];
  if (batches.empty()) return false;
  splice(free_.of[big], batches.back());  // (this one's list is empty)
  batches.pop_back();
  spares_->any[big].store(!batches.empty(), std::memory_order_relaxed);
  return true;
}

}  // namespace meldvm
