// How many stored values refer to each node: facts in the store, messages, aggregate inputs and
// heap objects (a list of nodes counts once per cell), not registers.
//
// Why: the established VM counts these references and deletes a created node as soon as it has
// no facts, no pending messages and no references (§6.10), at the end of the run in which that
// happened; `exists` then hands out the freed ids again, the last freed first. Programs that
// print created node ids (the established suite's mergesort) see the reuse. Only a serial Machine
// of a program that creates nodes counts; the Heap calls add/drop, the Machine reads count() and
// the nodes whose count fell to zero.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/value.hpp"

namespace meldvm {

class NodeReferences {
 public:
  // Ids at or past the current size (a node not created yet) are not counted.
  void resize(NodeId nodes) {
    if (nodes > counts_.size()) counts_.resize(nodes, 0);
  }
  void add(NodeId n) {
    if (n < counts_.size()) ++counts_[n];
  }
  void drop(NodeId n) {
    if (n < counts_.size() && counts_[n] != 0 && --counts_[n] == 0) dropped_.push_back(n);
  }
  std::uint32_t count(NodeId n) const { return n < counts_.size() ? counts_[n] : 0; }
  // The nodes whose count fell to zero since the last clearDropped(), in that order (repeats
  // possible); the caller checks whether each is still unreferenced.
  const std::vector<NodeId>& dropped() const { return dropped_; }
  void clearDropped() { dropped_.clear(); }

 private:
  std::vector<std::uint32_t> counts_;
  std::vector<NodeId> dropped_;
};

}  // namespace meldvm
