// The order in which the linear facts one node run sent to other nodes are delivered (§6.6).
//
// The established VM buffers them while the run goes on and hands them over when it ends, one
// destination after another: the first eight destinations in the order they were first sent to,
// any further ones by the address of their node record (increasing with the node id, since the
// initial nodes are allocated in id order). For one destination, one predicate after another in
// the order of their first fact; and for one destination and predicate, the facts in **reverse**
// sending order (each new fact goes to the front of its buffer). A receiver stores the facts in
// that order, and wakes up in that order, so programs whose result depends on the order of
// arrival (e.g. a counter that numbers the facts it consumes) need the same order to agree.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meldvm::detail {

class SendOrder {
 public:
  static constexpr std::size_t kFirstSeen = 8;  // destinations kept in first-send order

  // The indexes 0..n-1 of the sent facts in delivery order; nodeOf(i) and predOf(i) tell where
  // fact i goes and its predicate. The scratch space is kept, so steady-state runs allocate
  // nothing.
  template <class NodeOf, class PredOf>
  const std::vector<std::uint32_t>& arrange(std::size_t n, NodeOf nodeOf, PredOf predOf) {
    order_.clear();
    if (n <= kFirstSeen && distinctDestinations(n, nodeOf)) {
      // One fact per destination, all among the first eight: sending order (most runs).
      for (std::uint32_t i = 0; i < n; ++i) order_.push_back(i);
      return order_;
    }
    entries_.clear();
    seen_.clear();
    for (std::size_t i = 0; i < n; ++i)
      entries_.push_back({destinationKey(nodeOf(i)), std::uint64_t(predOf(i)), std::uint32_t(i)});
    // Group by (destination, predicate), sending order within a group; each group then sorts by
    // its destination and its first fact, and is delivered last fact first.
    std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
      return a.dest != b.dest ? a.dest < b.dest : a.pred != b.pred ? a.pred < b.pred : a.index < b.index;
    });
    if (std::adjacent_find(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
          return a.dest == b.dest;
        }) == entries_.end()) {  // one fact per destination: that order is final
      for (const Entry& e : entries_) order_.push_back(e.index);
      return order_;
    }
    groups_.clear();
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (i == 0 || entries_[i].dest != entries_[i - 1].dest || entries_[i].pred != entries_[i - 1].pred)
        groups_.push_back({entries_[i].dest, entries_[i].index, std::uint32_t(i), std::uint32_t(i)});
      groups_.back().end = std::uint32_t(i + 1);
    }
    std::sort(groups_.begin(), groups_.end(), [](const Group& a, const Group& b) {
      return a.dest != b.dest ? a.dest < b.dest : a.first < b.first;
    });
    for (const Group& g : groups_)
      for (std::uint32_t i = g.end; i-- > g.begin;) order_.push_back(entries_[i].index);
    return order_;
  }

 private:
  template <class NodeOf>
  static bool distinctDestinations(std::size_t n, NodeOf nodeOf) {
    for (std::size_t i = 1; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (nodeOf(i) == nodeOf(j)) return false;
    return true;
  }

  struct Entry {
    std::uint64_t dest;  // 0..7: the first destinations by first send; then kFirstSeen + node id
    std::uint64_t pred;
    std::uint32_t index;
  };
  struct Group {
    std::uint64_t dest;
    std::uint32_t first;  // index of the group's first fact
    std::uint32_t begin, end;
  };

  std::uint64_t destinationKey(std::uint64_t node) {
    for (std::size_t k = 0; k < seen_.size(); ++k)
      if (seen_[k] == node) return k;
    if (seen_.size() < kFirstSeen) {
      seen_.push_back(node);
      return seen_.size() - 1;
    }
    return kFirstSeen + node;
  }

  std::vector<std::uint64_t> seen_;
  std::vector<Entry> entries_;
  std::vector<Group> groups_;
  std::vector<std::uint32_t> order_;
};

}  // namespace meldvm::detail
