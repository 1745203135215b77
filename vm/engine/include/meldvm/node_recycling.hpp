// The ids of deleted created nodes, and when to delete one (§6.10), as the established VM does it.
//
// It counts the references that stored values hold to each node (node_references.hpp) and
// deletes a created node at the end of the node run in which it was left with no facts, no
// messages and no references; `exists` takes the most recently freed id first, from a stack of at
// most 32 (a further deleted id is not used again). Created node ids are visible in dumps and in
// facts, so a program that prints them (the established suite's mergesort) needs the same ids.
// Only a serial Machine of a program that creates nodes counts: threads number their created
// nodes from blocks of their own, and a robot cannot create nodes. Without counting, created
// nodes are collected once, when the run ends.
#pragma once

#include <cstddef>
#include <vector>

#include "meldvm/node_references.hpp"

namespace meldvm {

class NodeRecycling {
 public:
  explicit NodeRecycling(bool counting) : counting_(counting) {}
  bool counting() const { return counting_; }
  NodeReferences* references() { return counting_ ? &refs_ : nullptr; }
  const NodeReferences& refs() const { return refs_; }
  NodeReferences& refs() { return refs_; }
  void grow(NodeId nodes) {
    if (counting_) refs_.resize(nodes);
  }
  void freed(NodeId n) {
    if (freed_.size() < kKept) freed_.push_back(n);
  }
  bool reuse(NodeId& n) {
    if (freed_.empty()) return false;
    n = freed_.back();
    freed_.pop_back();
    return true;
  }

 private:
  static constexpr std::size_t kKept = 32;
  bool counting_;
  NodeReferences refs_;
  std::vector<NodeId> freed_;
};

}  // namespace meldvm
