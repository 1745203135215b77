#include "mailboxes.hpp"

#include <algorithm>
#include <stdexcept>

namespace meldvm {

Mailboxes::Mailboxes(std::vector<std::uint32_t> arities) : arity_(std::move(arities)) {
  // 32 words (four cache lines), or one record of the widest predicate when that is larger.
  std::uint32_t widest = 0;
  for (std::uint32_t a : arity_) widest = std::max(widest, a);
  chunkWords_ = std::max<std::uint32_t>(32, 2 + widest);
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
