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
  // The one field that holds a reference when it is a heap object's, else -1.
  std::int32_t soleObject() const {
    return objects_.size() == 1 && nodes_.empty() ? std::int32_t(objects_[0]) : -1;
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
