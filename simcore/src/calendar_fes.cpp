#include "simcore/calendar_fes.hpp"

#include <algorithm>

namespace simcore {

namespace {
constexpr std::uint64_t kReviewPeriod = 4096, kMaxWorkPerOperation = 8;
constexpr std::size_t kMinBuckets = 16;
constexpr std::size_t kWidthSample = 64;
}  // namespace

CalendarFes::CalendarFes() {
  buckets_.assign(kMinBuckets, kNil);
  tails_.assign(kMinBuckets, kNil);
}

void CalendarFes::clear() {
  pool_.clear();
  freeList_ = kNil;
  buckets_.assign(kMinBuckets, kNil);
  tails_.assign(kMinBuckets, kNil);
  width_ = 1000;
  size_ = 0;
  current_ = 0;
  currentTop_ = width_;
  located_ = kNil;
}

void CalendarFes::insertNode(std::uint32_t node) {
  const Event& e = pool_[node].event;
  const std::uint32_t b = bucketOf(e.time);
  // Appending is the common case (equal times in sequence order, like a burst scheduled at once):
  // the tail makes it O(1) instead of a walk through the whole list.
  if (buckets_[b] == kNil || !earlier(e, pool_[tails_[b]].event)) {
    pool_[node].next = kNil;
    (buckets_[b] == kNil ? buckets_[b] : pool_[tails_[b]].next) = node;
    tails_[b] = node;
    return;
  }
  std::uint32_t* link = &buckets_[b];
  while (*link != kNil && earlier(pool_[*link].event, e)) {
    link = &pool_[*link].next;
    ++work_;
  }
  pool_[node].next = *link;
  *link = node;
}

void CalendarFes::push(const Event& event) {
  std::uint32_t node;
  if (freeList_ != kNil) {
    node = freeList_;
    freeList_ = pool_[node].next;
    pool_[node].event = event;
  } else {
    node = std::uint32_t(pool_.size());
    pool_.push_back(Node{event, kNil});
  }
  if (size_ == 0 || event.time < currentTop_ - width_) {
    // An empty calendar has no meaningful "current" window, and an event before the current window
    // (a peek moved the window forward to a later event) would be missed by the next scan, which
    // starts at the current window: start the window at this event.
    current_ = bucketOf(event.time);
    currentTop_ = (event.time / width_ + 1) * width_;
  }
  insertNode(node);
  ++size_;
  if (located_ != kNil && earlier(event, pool_[buckets_[located_]].event)) located_ = kNil;
  if (size_ > 2 * buckets_.size()) {
    resize(buckets_.size() * 2);
  } else if (++operations_ == kReviewPeriod) {
    // Brown's calendar only re-sizes when the number of events changes, so a width estimated once
    // (say from the events at start-up) can stay wrong forever, leaving long lists or long runs of
    // empty buckets. Re-estimate when the average work per operation shows it.
    if (work_ > kReviewPeriod * kMaxWorkPerOperation) resize(buckets_.size());
    operations_ = work_ = 0;
  }
}

bool CalendarFes::locateEarliest() {
  const std::size_t nb = buckets_.size();
  std::uint32_t i = current_;
  SimTime top = currentTop_;
  for (std::size_t scanned = 0; scanned < nb; ++scanned) {
    const std::uint32_t head = buckets_[i];
    if (head != kNil && pool_[head].event.time < top) {
      current_ = i;
      currentTop_ = top;
      located_ = i;
      return true;
    }
    i = std::uint32_t((i + 1) & (nb - 1));
    top += width_;
    ++work_;
  }
  // A whole year without an event in its window: jump straight to the earliest head.
  std::uint32_t best = kNil;
  for (std::uint32_t b = 0; b < nb; ++b) {
    const std::uint32_t head = buckets_[b];
    if (head != kNil && (best == kNil || earlier(pool_[head].event, pool_[buckets_[best]].event))) best = b;
  }
  if (best == kNil) return false;
  const SimTime t = pool_[buckets_[best]].event.time;
  current_ = best;
  currentTop_ = (t / width_ + 1) * width_;
  located_ = best;
  return true;
}

const Event* CalendarFes::peek() {
  if (size_ == 0) return nullptr;
  if (located_ == kNil && !locateEarliest()) return nullptr;
  return &pool_[buckets_[located_]].event;
}

void CalendarFes::pop() {
  const std::uint32_t node = buckets_[located_];
  buckets_[located_] = pool_[node].next;
  if (buckets_[located_] == kNil) tails_[located_] = kNil;
  pool_[node].next = freeList_;
  freeList_ = node;
  located_ = kNil;
  --size_;
  if (buckets_.size() > kMinBuckets && size_ < buckets_.size() / 2) resize(buckets_.size() / 2);
}

SimTime CalendarFes::estimateWidth() {
  // Three times the mean gap between the earliest events: Brown's rule of thumb, which keeps a few
  // events per bucket in the part of the calendar being dequeued.
  sample_.clear();
  for (std::uint32_t head : buckets_)
    for (std::uint32_t n = head; n != kNil; n = pool_[n].next) sample_.push_back(pool_[n].event.time);
  const std::size_t k = std::min(sample_.size(), kWidthSample);
  if (k < 2) return width_;
  std::nth_element(sample_.begin(), sample_.begin() + (k - 1), sample_.end());
  std::sort(sample_.begin(), sample_.begin() + k);
  const SimTime span = sample_[k - 1] - sample_[0];
  if (span <= 0) return width_;
  const SimTime w = 3 * span / SimTime(k - 1);
  return w > 0 ? w : 1;
}

void CalendarFes::resize(std::size_t bucketCount) {
  const SimTime newWidth = estimateWidth();
  // Gather every node in ascending order of the old buckets, then rebuild.
  std::vector<std::uint32_t>& nodes = scratchNodes_;
  nodes.clear();
  for (std::uint32_t head : buckets_)
    for (std::uint32_t n = head; n != kNil; n = pool_[n].next) nodes.push_back(n);
  SimTime earliest = kTimeInfinity;
  for (std::uint32_t n : nodes) earliest = std::min(earliest, pool_[n].event.time);
  width_ = newWidth;
  buckets_.assign(bucketCount, kNil);
  tails_.assign(bucketCount, kNil);
  // Inserting in descending order makes every sorted insert hit the list head.
  std::sort(nodes.begin(), nodes.end(),
            [this](std::uint32_t a, std::uint32_t b) { return earlier(pool_[b].event, pool_[a].event); });
  for (std::uint32_t n : nodes) insertNode(n);
  located_ = kNil;
  if (earliest != kTimeInfinity) {
    current_ = bucketOf(earliest);
    currentTop_ = (earliest / width_ + 1) * width_;
  }
}

}  // namespace simcore
