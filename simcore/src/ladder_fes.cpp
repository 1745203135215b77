#include "simcore/ladder_fes.hpp"

#include <algorithm>

namespace simcore {

namespace {
// Sorting with "later first" puts the earliest event at the back, where pop_back takes it.
struct Later {
  bool operator()(const Event& a, const Event& b) const { return earlier(b, a); }
};
}  // namespace

void LadderFes::clear() {
  current_.clear();
  for (auto& b : buckets_) b.clear();
  rungBuckets_ = nextBucket_ = 0;
  rungStart_ = rungEnd_ = currentEnd_ = 0;
  width_ = 1;
  top_.clear();
  topMin_ = kTimeInfinity;
  topMax_ = 0;
  size_ = 0;
}

void LadderFes::push(const Event& e) {
  ++size_;
  if (e.time < currentEnd_) {
    // Rare (an event due within the current bucket's short window): keep the order by insertion.
    current_.insert(std::upper_bound(current_.begin(), current_.end(), e, Later{}), e);
  } else if (e.time < rungEnd_) {
    buckets_[std::size_t((e.time - rungStart_) / width_)].push_back(e);
  } else {
    top_.push_back(e);
    if (e.time < topMin_) topMin_ = e.time;
    if (e.time > topMax_) topMax_ = e.time;
  }
}

void LadderFes::rebuildRung() {
  const std::size_t n = top_.size();
  const SimTime span = topMax_ - topMin_;
  std::size_t count = std::clamp<std::size_t>(n / kTargetPerBucket, 1, kMaxBuckets);
  // Width rounded up so that count buckets cover [topMin_, topMax_] inclusive.
  width_ = span / SimTime(count) + 1;
  count = std::size_t(span / width_) + 1;
  if (buckets_.size() < count) buckets_.resize(count);
  rungBuckets_ = count;
  nextBucket_ = 0;
  rungStart_ = topMin_;
  rungEnd_ = rungStart_ + SimTime(count) * width_;
  for (const Event& e : top_) buckets_[std::size_t((e.time - rungStart_) / width_)].push_back(e);
  top_.clear();
  topMin_ = kTimeInfinity;
  topMax_ = 0;
}

bool LadderFes::advance() {
  for (;;) {
    while (nextBucket_ < rungBuckets_) {
      std::vector<Event>& b = buckets_[nextBucket_++];
      if (b.empty()) continue;
      current_.swap(b);  // b keeps current_'s old (empty) capacity
      currentEnd_ = rungStart_ + SimTime(nextBucket_) * width_;
      std::sort(current_.begin(), current_.end(), Later{});
      return true;
    }
    if (top_.empty()) return false;
    rebuildRung();
  }
}

const Event* LadderFes::peek() {
  if (current_.empty() && !advance()) return nullptr;
  return &current_.back();
}

void LadderFes::pop() {
  current_.pop_back();
  --size_;
}

}  // namespace simcore
