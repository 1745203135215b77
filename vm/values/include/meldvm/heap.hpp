// Reference-counted objects for the boxed Meld values (string, list, struct, array, set).
//
// Why reference counting on a private slab heap: facts are created and consumed at a high rate and
// most of them carry only scalars, but lists (paths, collected values) and strings do flow through
// facts and messages. Sharing by reference count makes copying a value into a fact, a message or a
// register one increment, lets lists share their tails (cons is O(1), `[H | T]` needs no copy), and
// frees memory at once when the last fact holding it is consumed. Objects come from size-class free
// lists carved out of 64 KiB slabs, so in the steady state an object is recycled, never malloc'd.
// Every object records its own TypeId, so releasing one needs no outside type information.
// Counts are not atomic: one Heap serves one thread (the serial VM; the threaded VM will need one
// heap per thread plus a hand-over rule for values that cross threads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "meldvm/types.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

struct Object {
  std::uint32_t refs;
  TypeId type;
};

// A list is a chain of cons cells; the empty list is the nil value (null pointer).
struct ConsCell : Object {
  Value head;
  ConsCell* tail;
};

// Strings: length, then the bytes (not NUL-terminated).
struct StringObject : Object {
  std::uint32_t length;
  const char* chars() const { return reinterpret_cast<const char*>(this + 1); }
};

// Structs, arrays and sets: a size, then the items.
struct TupleObject : Object {
  std::uint32_t size;
  std::uint32_t capacity;  // items the block was allocated for (a set may drop duplicates)
  const Value* items() const { return reinterpret_cast<const Value*>(this + 1); }
};

inline std::string_view stringOf(Value v) {
  const auto* s = static_cast<const StringObject*>(v.asObject());
  return {s->chars(), s->length};
}
inline Value listHead(Value list) { return static_cast<const ConsCell*>(list.asObject())->head; }
inline Value listTail(Value list) {
  return Value::fromObject(static_cast<const ConsCell*>(list.asObject())->tail);
}
inline std::span<const Value> tupleItems(Value v) {
  const auto* t = static_cast<const TupleObject*>(v.asObject());
  return {t->items(), t->size};
}

class Heap {
 public:
  explicit Heap(const TypeTable& types) : types_(types) {}
  ~Heap();
  Heap(const Heap&) = delete;
  Heap& operator=(const Heap&) = delete;

  const TypeTable& types() const { return types_; }

  // Builders. Inputs are borrowed (the heap takes its own references to what it stores); the
  // result is a new reference that the caller owns and must release.
  Value makeString(std::string_view s);
  Value cons(TypeId listType, Value head, Value tail);
  Value makeList(TypeId listType, std::span<const Value> items, Value tail = Value::nil());  // items ++ tail
  // Struct, array or set (`type` says which); a set keeps the first copy of equal items.
  Value makeTuple(TypeId type, std::span<const Value> items);

  // No-ops for unboxed types and for nil.
  void retain(TypeId t, Value v) {
    if (types_.boxed(t) && !v.isNil()) ++v.asObject()->refs;
  }
  void release(TypeId t, Value v) {
    if (types_.boxed(t) && !v.isNil() && --v.asObject()->refs == 0) destroy(v.asObject());
  }

  std::size_t liveObjects() const { return live_; }
  std::size_t bytesInUse() const { return bytesInUse_; }
  std::size_t bytesReserved() const { return bytesReserved_; }

 private:
  static constexpr std::size_t kSlabBytes = 64 * 1024;
  static constexpr std::size_t kSmallMax = 512;  // small blocks: 8-byte size classes
  static constexpr std::size_t kSmallClasses = kSmallMax / 8;
  static constexpr std::size_t kLargeClasses = 40;  // large blocks: power-of-two classes

  struct FreeBlock {
    FreeBlock* next;
  };

  static std::size_t classOf(std::size_t bytes);
  static std::size_t classBytes(std::size_t cls);
  void* allocate(std::size_t bytes);  // raw block; the builder constructs the object
  ConsCell* newCell(TypeId listType);
  void deallocate(Object* o, std::size_t bytes);
  std::size_t objectBytes(const Object* o) const;
  void destroy(Object* o);  // count reached zero: release children, recycle the block

  const TypeTable& types_;
  FreeBlock* free_[kSmallClasses + kLargeClasses] = {};
  std::vector<void*> slabs_;
  std::vector<void*> large_;
  char* bump_ = nullptr;
  char* bumpEnd_ = nullptr;
  std::size_t live_ = 0, bytesInUse_ = 0, bytesReserved_ = 0;
};

}  // namespace meldvm
