// The fields of a relation whose values hold references (heap objects, and nodes where the Heap
// counts them), worked out once from the field types, and the retaining and releasing of the
// references of one stored copy of its arguments (a fact, a message, an aggregate input).
//
// Why: every fact stored or dropped retains or releases its arguments. Walking all the fields and
// looking each one's type up (Heap::retainStored) cost more than the reference counting itself on
// facts that carry a list; this walks only the fields that hold references, already sorted into
// objects and nodes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "meldvm/heap.hpp"

namespace meldvm {

class ReferenceFields {
 public:
  ReferenceFields() = default;
  ReferenceFields(const Heap& heap, std::span<const TypeId> fields) {
    const TypeTable& types = heap.types();
    for (std::uint32_t i = 0; i < fields.size(); ++i) {
      if (types.boxed(fields[i]))
        objects_.push_back(i);
      else if (heap.holdsReferences(fields[i]))
        nodes_.push_back(i);
    }
  }

  // No field holds a reference: copies of the arguments are plain words.
  bool empty() const { return objects_.empty() && nodes_.empty(); }
  // Some field holds a heap object and none a counted node: a copy retains objects only.
  bool objectsOnly() const { return !objects_.empty() && nodes_.empty(); }
  // The references of a copy in one byte, for the paths that copy or drop one fact at a time
  // (a message with its list, a consumed fact): kNoReferences; the index of the only field that
  // holds one, when it holds a heap object and is below 128; else kSeveralReferences (retain and
  // release walk them).
  static constexpr std::int8_t kNoReferences = -1, kSeveralReferences = -2;
  std::int8_t pattern() const {
    if (empty()) return kNoReferences;
    if (objects_.size() == 1 && nodes_.empty() && objects_[0] < 128) return std::int8_t(objects_[0]);
    return kSeveralReferences;
  }
  void retain(Heap& heap, const Value* args) const {
    for (std::uint32_t i : objects_) heap.retainObjectValue(args[i]);
    for (std::uint32_t i : nodes_) heap.retainNode(args[i]);
  }
  void release(Heap& heap, const Value* args) const {
    for (std::uint32_t i : objects_) heap.releaseObject(args[i]);
    for (std::uint32_t i : nodes_) heap.releaseNode(args[i]);
  }

 private:
  std::vector<std::uint32_t> objects_;  // boxed fields
  std::vector<std::uint32_t> nodes_;    // node fields of a Heap that counts node references
};

}  // namespace meldvm
