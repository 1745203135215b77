#include "mailboxes.hpp"

#include <algorithm>

namespace meldvm {

Mailboxes::Mailboxes(std::uint32_t maxArity)
    : recordWords_(1 + maxArity),
      perChunk_(std::max<std::uint32_t>(2, 31 / recordWords_)),
      chunkWords_(1 + perChunk_ * recordWords_) {}

std::uint32_t Mailboxes::newChunk() {
  std::uint32_t c;
  if (free_ != kNone) {
    c = free_;
    free_ = std::uint32_t(words_[std::size_t(c) * chunkWords_].bits());
  } else {
    c = std::uint32_t(words_.size() / chunkWords_);
    words_.resize(words_.size() + chunkWords_);
  }
  words_[std::size_t(c) * chunkWords_] = Value::fromBits(kNone);  // next = none, count = 0
  return c;
}

}  // namespace meldvm
