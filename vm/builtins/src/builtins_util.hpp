// Helpers shared by the builtins_*.cpp files (not installed).
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "meldvm/builtins.hpp"

namespace meldvm::builtins {

inline TypeId objectType(Value v) { return v.asObject()->type; }

inline std::size_t listLength(Value l) {
  std::size_t n = 0;
  for (; !l.isNil(); l = listTail(l)) ++n;
  return n;
}

// A new reference to `v` of type `t` (for results that are an argument or one of its parts).
inline Value retained(Heap& heap, TypeId t, Value v) {
  heap.retain(t, v);
  return v;
}

// Builds a list front to back: each cell is appended behind the previous one, so no reversal or
// temporary buffer is needed. `finish` hands over the list (a new reference).
class ListBuilder {
 public:
  ListBuilder(Heap& heap, TypeId listType)
      : heap_(heap),
        type_(listType),
        item_(heap.types().element(listType)),
        itemHolds_(heap.holdsReferences(item_)) {}
  ~ListBuilder() { heap_.release(type_, head_); }  // only if finish() was not reached (exception)
  ListBuilder(const ListBuilder&) = delete;
  ListBuilder& operator=(const ListBuilder&) = delete;

  void push(Value item) {
    if (itemHolds_) heap_.retainStored(item_, item);
    ConsCell* cell = heap_.lastCell(type_, item);
    if (last_)
      last_->tail = cell;
    else
      head_ = Value::fromObject(cell);
    last_ = cell;
  }
  // Shares `rest` as the tail of the list built so far.
  Value finish(Value rest = Value::nil()) {
    heap_.retain(type_, rest);
    if (last_)
      last_->tail = static_cast<ConsCell*>(rest.asObject());
    else
      head_ = rest;
    const Value out = head_;
    head_ = Value::nil();
    last_ = nullptr;
    return out;
  }

 private:
  Heap& heap_;
  TypeId type_;
  TypeId item_;
  bool itemHolds_;  // the items are heap objects or counted nodes: each one is retained
  Value head_ = Value::nil();
  ConsCell* last_ = nullptr;
};

inline RuntimeError error(std::string_view fn, const std::string& what) {
  return RuntimeError(std::string(fn) + ": " + what);
}

}  // namespace meldvm::builtins
