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
    Shape s{std::uint32_t(fields.size()), 0, 0, fields.size() <= kMaxNarrowArity};
    for (std::uint32_t i = 0; i < fields.size(); ++i) {
      if (fields[i] == ArgWidth::Word) s.narrow = false;
      if (fields[i] == ArgWidth::Int32) s.signMask |= std::uint32_t(1) << (i % 32);
    }
    s.words = s.narrow ? 1 + s.arity / 2 : 1 + s.arity;
    widest = std::max(widest, s.words);
    shape_.push_back(s);
  }
  // 32 words (four cache lines), or one record of the widest predicate when that is larger.
  chunkWords_ = std::max<std::uint32_t>(32, 1 + widest);
}

Mailboxes::~Mailboxes() {
  for (std::uint32_t s = 0; s < slabCount_; ++s)
    LargeAllocator<Value>().deallocate(table_[firstSlab_ + s], std::size_t(slabCapacity(s)) * chunkWords_);
}

std::uint32_t Mailboxes::newChunk() {
  std::uint32_t c;
  if (free_ != kNone || (spares_ && takeSpares())) {
    c = free_;
    free_ = std::uint32_t(chunk(c)[0].bits());
    --freeChunks_;
  } else {
    if (slabCount_ == 0 || slabUsed_ == slabCapacity(slabCount_ - 1)) {
      const std::uint32_t slab = firstSlab_ + slabCount_;
      // (The table's last slab is never used: its last chunk's id would be kNone.)
      if (slab >= endSlab_ || slab == MailSlabs::kSlabs - 1)
        throw std::length_error("meldvm: too many messages in transit");
      table_[slab] = LargeAllocator<Value>().allocate(std::size_t(slabCapacity(slabCount_)) * chunkWords_);
      ++slabCount_;
      slabUsed_ = 0;
    }
    c = ((firstSlab_ + slabCount_ - 1) << kSlabShift) | slabUsed_++;
  }
  chunk(c)[0] = Value::fromBits(kNone);  // next = none, no words used
  return c;
}

void Mailboxes::giveSpares(std::uint32_t head, std::uint32_t tail, std::uint32_t chunks) {
  std::lock_guard<std::mutex> lock(spares_->lock);
  chunk(tail)[0] = Value::fromBits(spares_->head);
  spares_->head = head;
  spares_->chunks += chunks;
  spares_->any.store(true, std::memory_order_relaxed);
}

bool Mailboxes::takeSpares() {
  if (!spares_->any.load(std::memory_order_relaxed)) return false;  // a hint: the lock decides
  std::lock_guard<std::mutex> lock(spares_->lock);
  if (spares_->head == kNone) return false;
  free_ = spares_->head;  // (this one's list is empty)
  freeChunks_ = spares_->chunks;
  spares_->head = kNone;
  spares_->chunks = 0;
  spares_->any.store(false, std::memory_order_relaxed);
  return true;
}

}  // namespace meldvm
