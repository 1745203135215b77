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

  // The indexes 0..n-1 of the sent facts in delivery order, or nullptr when that is the sending
  // order (0, 1, ..., n - 1: most runs); nodeOf(i) and predOf(i) tell where fact i goes and its
  // predicate. In time linear in n, but for sorting the destinations past the
  // first eight (a comparison sort of the facts was a fifth of all the instructions of
  // 8queens-12, whose node runs send thousands of facts). The scratch space is kept, so
  // steady-state runs allocate nothing.
  template <class NodeOf, class PredOf>
  const std::vector<std::uint32_t>* arrange(std::size_t n, NodeOf nodeOf, PredOf predOf) {
    order_.clear();
    if (inSendingOrder(n, nodeOf, predOf)) return nullptr;  // most runs: a comprehension over the neighbours
    dests_.clear();
    groups_.clear();
    next_.resize(n);
    startLookup();
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t d = destinationOf(nodeOf(i));
      const std::uint64_t pred = predOf(i);
      std::uint32_t g = dests_[d].firstGroup;
      while (g != kNone && groups_[g].pred != pred) g = groups_[g].sibling;
      if (g == kNone) {  // a new (destination, predicate): after the destination's others
        g = std::uint32_t(groups_.size());
        groups_.push_back({pred, kNone, kNone});
        (dests_[d].firstGroup == kNone ? dests_[d].firstGroup : groups_[dests_[d].lastGroup].sibling) = g;
        dests_[d].lastGroup = g;
      }
      next_[i] = groups_[g].head;  // in front: a group is delivered last fact first
      groups_[g].head = i;
    }
    // The first eight destinations in first-send order (dests_ is in that order), the others by node.
    if (dests_.size() > kFirstSeen)
      std::sort(dests_.begin() + kFirstSeen, dests_.end(),
                [](const Destination& a, const Destination& b) { return a.node < b.node; });
    for (const Destination& d : dests_)
      for (std::uint32_t g = d.firstGroup; g != kNone; g = groups_[g].sibling)
        for (std::uint32_t i = groups_[g].head; i != kNone; i = next_[i]) order_.push_back(i);
    return &order_;
  }

  // The scratch space's memory (MemoryUse::buffers).
  std::size_t bytesReserved() const {
    return dests_.capacity() * sizeof(Destination) + groups_.capacity() * sizeof(Group) +
           (next_.capacity() + order_.capacity()) * sizeof(std::uint32_t) + table_.capacity() * sizeof(Slot);
  }

 private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

  // Whether the delivery order is the sending order: each destination's facts were sent one after
  // the other, at most one of each predicate, and the destinations past the first eight in
  // increasing node order. A run that sends each neighbour a fact or two (heat-transfer,
  // pagerank) then costs a pass over its facts instead of building the groups.
  template <class NodeOf, class PredOf>
  static bool inSendingOrder(std::size_t n, NodeOf nodeOf, PredOf predOf) {
    std::uint64_t firstSeen[kFirstSeen];
    std::size_t destinations = 0, start = 0;  // start: the first fact of the current destination
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t node = nodeOf(i);
      if (i > 0 && node == nodeOf(start)) {
        const std::uint64_t pred = predOf(i);
        for (std::size_t j = start; j < i; ++j)
          if (predOf(j) == pred) return false;  // a group of two or more: delivered last first
        continue;
      }
      for (std::size_t k = 0; k < std::min(destinations, kFirstSeen); ++k)
        if (firstSeen[k] == node) return false;  // sent to again after another destination
      if (destinations < kFirstSeen)
        firstSeen[destinations] = node;
      else if (destinations > kFirstSeen && node <= nodeOf(start))
        return false;  // past the first eight, delivered by node id
      start = i;
      ++destinations;
    }
    return true;
  }

  struct Destination {
    std::uint64_t node;
    std::uint32_t firstGroup, lastGroup;  // its predicates, in the order of their first fact
  };
  struct Group {
    std::uint64_t pred;
    std::uint32_t head;     // its last fact; next_ leads to the earlier ones
    std::uint32_t sibling;  // the destination's next group
  };
  // Node -> index in dests_, by open addressing; a slot belongs to this run if its stamp is the
  // run's, so nothing is cleared between runs.
  struct Slot {
    std::uint64_t node;
    std::uint32_t stamp, dest;
  };

  // A fresh lookup for this run: no slot carries the new stamp. The table keeps its size.
  void startLookup() {
    if (table_.empty()) table_.assign(16, Slot{0, 0, 0});
    if (++stamp_ == 0) {  // wrapped around: old stamps could match again
      std::fill(table_.begin(), table_.end(), Slot{0, 0, 0});
      stamp_ = 1;
    }
  }
  std::uint32_t destinationOf(std::uint64_t node) {
    for (std::size_t k = home(node);; k = (k + 1) & (table_.size() - 1)) {
      Slot& s = table_[k];
      if (s.stamp != stamp_) {
        s = Slot{node, stamp_, std::uint32_t(dests_.size())};
        dests_.push_back({node, kNone, kNone});
        // At most half full, sized by the destinations, not by the facts sent.
        if (dests_.size() * 2 > table_.size()) grow();
        return std::uint32_t(dests_.size() - 1);
      }
      if (s.node == node) return s.dest;
    }
  }
  std::size_t home(std::uint64_t node) const {
    return std::size_t((node * 0x9E3779B97F4A7C15ull) >> 32) & (table_.size() - 1);
  }
  void grow() {  // twice the slots, this run's destinations placed again (dests_ is unsorted yet)
    table_.assign(table_.size() * 2, Slot{0, 0, 0});
    stamp_ = 1;
    for (std::uint32_t d = 0; d < dests_.size(); ++d) {
      std::size_t k = home(dests_[d].node);
      while (table_[k].stamp == stamp_) k = (k + 1) & (table_.size() - 1);
      table_[k] = Slot{dests_[d].node, stamp_, d};
    }
  }

  std::vector<Destination> dests_;
  std::vector<Group> groups_;
  std::vector<std::uint32_t> next_;
  std::vector<Slot> table_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> order_;
};

}  // namespace meldvm::detail
