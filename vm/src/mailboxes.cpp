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

void Mailboxes::post(NodeId dest, PredId p, bool negative, const Value* args, std::uint32_t arity) {
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
  std::copy(args, args + arity, r + 1);
  head = Value::fromBits((head.bits() & 0xFFFFFFFFull) | ((count + 1) << 32));
}

}  // namespace meldvm
