#include "meldvm/group_inputs.hpp"

#include <algorithm>
#include <stdexcept>

#include "meldvm/value_ops.hpp"

namespace meldvm {

GroupInputs::GroupInputs(const TypeTable& types, Heap& heap, std::vector<TypeId> fields)
    : types_(types), heap_(heap), fields_(std::move(fields)), references_(heap_, fields_) {
  for (std::uint32_t i = 0; i < fields_.size(); ++i)
    integerKeys_ = integerKeys_ && integerLike(types_, fields_[i]);
  stride_ = 1 + std::uint32_t(fields_.size());
  scratch_.reserve(fields_.size());
}

GroupInputs::~GroupInputs() {
  if (references_.empty()) return;
  for (NodeId n = 0; n < runs_.size(); ++n)
    for (std::uint32_t i = 0; i < runs_[n].size; ++i) references_.release(heap_, args(n, i));
}

std::uint32_t GroupInputs::findAny(NodeId n, const Value* a) const {
  const Run& r = runs_[n];
  const Value* rec = words_.data() + r.offset + 1;
  const std::uint32_t arity = stride_ - 1;
  for (std::uint32_t i = 0; i < r.size; ++i, rec += stride_) {
    std::uint32_t k = 0;
    if (integerKeys_)  // equal bits are equal values
      while (k < arity && rec[k].bits() == a[k].bits()) ++k;
    else
      while (k < arity && valuesEqualFast(types_, fields_[k], rec[k], a[k])) ++k;
    if (k == arity) return i;
  }
  return kNone;
}

std::uint32_t GroupInputs::allocate(std::uint32_t sizeClass) {
  if (sizeClass >= freeRuns_.size()) freeRuns_.resize(sizeClass + 1, kNone);
  if (const std::uint32_t head = freeRuns_[sizeClass]; head != kNone) {
    freeRuns_[sizeClass] = std::uint32_t(words_[head].bits());
    return head;
  }
  const std::size_t words = (std::size_t(2) << sizeClass) * stride_;
  if (words_.size() + words > kNone) throw std::length_error("meldvm: too many aggregate inputs");
  const std::uint32_t offset = std::uint32_t(words_.size());
  words_.resize(words_.size() + words);
  return offset;
}

void GroupInputs::free(std::uint32_t offset, std::uint32_t sizeClass) {
  words_[offset] = Value::fromBits(freeRuns_[sizeClass]);
  freeRuns_[sizeClass] = offset;
}

void GroupInputs::append(NodeId n, const Value* a, std::uint32_t count) {
  references_.retain(heap_, a);
  Run& r = runs_[n];
  if (r.sizeClass == kNone || r.size == (std::uint32_t(2) << r.sizeClass)) {
    // `a` may point into words_, which allocate() may move: copy it first.
    scratch_.assign(a, a + (stride_ - 1));
    a = scratch_.data();
    const std::uint32_t cls = r.sizeClass == kNone ? 0 : r.sizeClass + 1;
    const std::uint32_t offset = allocate(cls);
    Run& grown = runs_[n];
    if (grown.sizeClass != kNone) {
      std::copy_n(words_.begin() + grown.offset, std::size_t(grown.size) * stride_, words_.begin() + offset);
      free(grown.offset, grown.sizeClass);
    }
    grown.offset = offset;
    grown.sizeClass = cls;
    Value* rec = words_.data() + offset + std::size_t(grown.size) * stride_;
    rec[0] = Value::fromBits(count);
    std::copy(a, a + (stride_ - 1), rec + 1);
    ++grown.size;
    return;
  }
  Value* rec = words_.data() + r.offset + std::size_t(r.size) * stride_;
  rec[0] = Value::fromBits(count);
  std::copy(a, a + (stride_ - 1), rec + 1);
  ++r.size;
}

void GroupInputs::erase(NodeId n, std::uint32_t i) {
  Run& r = runs_[n];
  Value* rec = releaseRecord(r, i);
  std::copy(rec + stride_, words_.data() + r.offset + std::size_t(r.size) * stride_, rec);
  dropLast(r);
}

void GroupInputs::eraseUnordered(NodeId n, std::uint32_t i) {
  Run& r = runs_[n];
  Value* rec = releaseRecord(r, i);
  const Value* last = words_.data() + r.offset + std::size_t(r.size - 1) * stride_;
  for (std::uint32_t k = 0; k < stride_; ++k) rec[k] = last[k];  // a word or two: no memmove call
  dropLast(r);
}

Value* GroupInputs::releaseRecord(const Run& r, std::uint32_t i) {
  Value* rec = words_.data() + r.offset + std::size_t(i) * stride_;
  references_.release(heap_, rec + 1);
  return rec;
}

void GroupInputs::giveBack(Run& r) {
  free(r.offset, r.sizeClass);
  r = Run{};
}

void GroupInputs::clear(NodeId n) {
  while (runs_[n].size != 0) erase(n, runs_[n].size - 1);
}

}  // namespace meldvm
