#include "meldvm/list_sharing.hpp"

#include "meldvm/value_ops.hpp"

namespace meldvm {

ListEncoderShare::ListEncoderShare(ListEncoderShare&& o) noexcept
    : heap_(o.heap_), numbers_(std::move(o.numbers_)), held_(std::move(o.held_)) {
  o.numbers_ = SlotHash();
  o.held_.clear();
}

void ListEncoderShare::sent(TypeId listType, Value cell) {
  numbers_.insert(hashOf(cell.asObject()), std::uint32_t(held_.size()));
  heap_->retain(listType, cell);
  held_.emplace_back(listType, cell);
}

void ListEncoderShare::reset() {
  // The table keeps its room (the next batch allocates nothing); the entries go one by one.
  for (std::uint32_t n = 0; n < held_.size(); ++n) numbers_.erase(hashOf(held_[n].second.asObject()), n);
  for (const auto& [t, v] : held_) heap_->release(t, v);
  held_.clear();
}

void ListDecoderShare::built(TypeId listType, Value list, std::uint32_t count) {
  for (std::uint32_t i = 0; i < count; ++i, list = listTail(list)) {
    heap_.retain(listType, list);
    cells_.emplace_back(listType, list);
  }
}

void ListDecoderShare::reset() {
  for (const auto& [t, v] : cells_) heap_.release(t, v);
  cells_.clear();
}

}  // namespace meldvm
