#include "meldvm/mailboxes.hpp"

#include <algorithm>
#include <stdexcept>

namespace meldvm {

Mailboxes::Mailboxes(const std::vector<std::vector<ArgWidth>>& shapes) {
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
  for (std::size_t s = 0; s < slabs_.size(); ++s)
    LargeAllocator<Value>().deallocate(slabs_[s], std::size_t(slabCapacity(s)) * chunkWords_);
}

std::uint32_t Mailboxes::newChunk() {
  std::uint32_t c;
  if (free_ != kNone) {
    c = free_;
    free_ = std::uint32_t(chunk(c)[0].bits());
  } else {
    if (slabs_.empty() || slabUsed_ == slabCapacity(slabs_.size() - 1)) {
      if (slabs_.size() == (std::size_t(1) << (32 - kSlabShift)) - 1)
        throw std::length_error("meldvm: too many messages in transit");
      slabs_.reserve(slabs_.size() + 1);  // no leak if the push_back would throw
      slabs_.push_back(
          LargeAllocator<Value>().allocate(std::size_t(slabCapacity(slabs_.size())) * chunkWords_));
      slabUsed_ = 0;
    }
    c = std::uint32_t(((slabs_.size() - 1) << kSlabShift) | slabUsed_++);
  }
  chunk(c)[0] = Value::fromBits(kNone);  // next = none, no words used
  return c;
}

}  // namespace meldvm
