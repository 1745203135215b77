// Reference-counted objects for the boxed Meld values (string, list, struct, array, set).
//
// Why reference counting on a private slab heap: facts are created and consumed at a high rate and
// most of them carry only scalars, but lists (paths, collected values) and strings do flow through
// facts and messages. Sharing by reference count makes copying a value into a fact, a message or a
// register one increment, lets lists share their tails (cons is O(1), `[H | T]` needs no copy), and
// frees memory at once when the last fact holding it is consumed. Objects come from size-class free
// lists carved out of 64 KiB slabs, so in the steady state an object is recycled, never malloc'd.
// Every object records its own TypeId, so releasing one needs no outside type information.
//
// One Heap serves one thread. A value that goes to another thread (`meld -j N`: a fact for
// another shard's node, a node that moves) is handed over, not copied: share() marks it and all it
// reaches *shared* (the top bit of its count), and from then on its count changes atomically.
// Shared objects never become private again and point only at shared objects, so a private
// object is reachable from its own thread alone and keeps its plain, non-atomic count (the serial
// VM never shares anything). The thread that drops a shared object's last reference destroys it;
// its block goes back to the heap that allocated it (found from the block's address) through that
// heap's remote-free stack, which the owner drains when it allocates. (A dead list cell's tail is
// dropped a few deaths later, by the same thread: destroy(). So a block another thread frees may
// come back only when that thread's ring comes round, or when it counts its own objects.)
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <string_view>
#include <vector>

#include "meldvm/node_references.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value.hpp"
#include "support/large_allocator.hpp"

namespace meldvm {

struct Object {
  std::uint32_t refs;  // the count; kShared: shared between threads (changed atomically)
  TypeId type;
  static constexpr std::uint32_t kShared = 0x80000000u;
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
  // nodes: where the node references of stored values are counted (node_references.hpp), if any.
  explicit Heap(const TypeTable& types, NodeReferences* nodes = nullptr) : types_(types), nodes_(nodes) {}
  ~Heap();
  Heap(const Heap&) = delete;
  Heap& operator=(const Heap&) = delete;

  const TypeTable& types() const { return types_; }

  // Builders. Inputs are borrowed (the heap takes its own references to what it stores); the
  // result is a new reference that the caller owns and must release.
  Value makeString(std::string_view s);
  Value cons(TypeId listType, Value head, Value tail);
  // A list's new last cell, its tail nil, for a builder that retains `head` itself where the item
  // type holds references (holdsReferences): cons without the call and the type tests per cell.
  ConsCell* lastCell(TypeId listType, Value head) {
    ConsCell* c = newCell(listType);
    c->head = head;
    c->tail = nullptr;
    return c;
  }
  Value makeList(TypeId listType, std::span<const Value> items, Value tail = Value::nil());  // items ++ tail
  // Struct, array or set (`type` says which); a set keeps the first copy of equal items.
  Value makeTuple(TypeId type, std::span<const Value> items);
  // A struct or array of `size` items that hold no references (the float structs of belief
  // propagation), built in place: result gets the new object (a reference the caller owns), the
  // items are returned for the caller to write, every one, before anything can read or release
  // the object (they start as whatever the block held).
  // Inline for a struct type seen before (belief-propagation-50 makes 3.6 million of them).
  Value* makePlainTuple(TypeId type, std::uint32_t size, Value& result) {
    if (type < plainStructFields_.size() && plainStructFields_[type] == size) [[likely]] {
      TupleObject* t = newPlainTuple(type, size);
      result = Value::fromObject(t);
      return reinterpret_cast<Value*>(t + 1);
    }
    return makePlainTupleChecked(type, size, result);
  }

  // No-ops for unboxed types and for nil.
  void retain(TypeId t, Value v) {
    if (types_.boxed(t)) retainObjectValue(v);
  }
  void release(TypeId t, Value v) {
    if (types_.boxed(t)) releaseObject(v);
  }
  // release() of a value whose type is boxed (a register known to hold one).
  void releaseObject(Value v) {
    if (!v.isNil() && dropReference(v.asObject())) destroy(v.asObject());
  }
  // retainStored / releaseStored of a value known to be a heap object (or nil), or a node this
  // Heap counts (ReferenceFields sorts the fields once).
  void retainObjectValue(Value v) {
    if (!v.isNil()) retainObject(v.asObject());
  }
  void retainNode(Value v) { nodes_->add(v.asNode()); }
  void releaseNode(Value v) { nodes_->drop(v.asNode()); }
  // A reference that a stored value holds (a fact, a message, an aggregate input, an item of a heap
  // object; not a register): as retain/release, and a node counts in the NodeReferences, if any.
  bool holdsReferences(TypeId t) const {
    return types_.boxed(t) || (nodes_ && types_.kind(t) == TypeKind::Node);
  }
  void retainStored(TypeId t, Value v) {
    if (types_.boxed(t))
      retainObjectValue(v);
    else if (nodes_ && types_.kind(t) == TypeKind::Node)
      retainNode(v);
  }
  void releaseStored(TypeId t, Value v) {
    if (types_.boxed(t))
      releaseObject(v);
    else if (nodes_ && types_.kind(t) == TypeKind::Node)
      releaseNode(v);
  }
  // Marks v and everything it reaches shared, before v is handed to another thread.
  void share(TypeId t, Value v);
  // share() for many objects that are likely cold (a moving node's facts): each one is fetched
  // some objects ahead, and a list's second cell halfway there.
  void shareAll(std::span<Object* const> objects);

  // Drops the references to the tails of dead list cells that destroy() put off (below).
  void dropDeferredTails();

  // Objects and bytes of this heap's blocks (the blocks other threads freed count once drained).
  std::size_t liveObjects() {
    dropDeferredTails();
    drainRemote();
    return live_;
  }
  std::size_t bytesInUse() {
    dropDeferredTails();
    drainRemote();
    return bytesInUse_;
  }
  std::size_t bytesReserved() const { return bytesReserved_; }

  // What native code reads and writes to take a list cell itself (native_abi.h, meld_native_heap):
  // the free list of cells' size class, the current slab's room, the counts.
  struct CellAllocation {
    void** freeList;
    char** bump;
    char* const* bumpEnd;
    std::size_t* live;
    std::size_t* bytesInUse;
  };
  CellAllocation cellAllocationForNativeCode() {
    static_assert(sizeof(FreeBlock*) == sizeof(void*) && sizeof(ConsCell) == 24);
    return {reinterpret_cast<void**>(&free_[smallClassOf(sizeof(ConsCell))]), &bump_, &bumpEnd_, &live_,
            &bytesInUse_};
  }

 private:
  static constexpr std::size_t kSlabBytes = 64 * 1024;
  // A heap past kSlabsAlone slabs (2 MiB) takes them from chunks of huge pages (support's large
  // allocator): the list cells of a big run are walked at random, and with 4 KiB pages nearly
  // every step also missed the TLB. Small heaps (a robot's) keep small slabs.
  static constexpr std::size_t kSlabsAlone = 32;
  static constexpr std::size_t kChunkBytes = support::kHugePage;
  static constexpr std::size_t kSmallMax = 512;  // small blocks: 8-byte size classes
  static constexpr std::size_t kSmallClasses = kSmallMax / 8;
  static constexpr std::size_t kLargeClasses = 40;  // large blocks: power-of-two classes

  struct FreeBlock {
    FreeBlock* next;
  };
  struct RemoteBlock {  // a block another thread freed, on its owner's remote-free stack
    RemoteBlock* next;
    std::uint64_t cls;
  };
  // Where the owning Heap's address sits: the start of a small block's (aligned) slab, the
  // header in front of a large block.
  static constexpr std::size_t kOwnerBytes = 16;

  // Another thread may be changing a shared object's count: its bit is read atomically.
  static bool isShared(Object* o) {
    return std::atomic_ref<std::uint32_t>(o->refs).load(std::memory_order_relaxed) & Object::kShared;
  }
  static void retainObject(Object* o) {
    if (std::atomic_ref<std::uint32_t> refs(o->refs); refs.load(std::memory_order_relaxed) & Object::kShared)
      refs.fetch_add(1, std::memory_order_relaxed);
    else
      ++o->refs;
  }
  // Drops one reference; true if it was the last.
  static bool dropReference(Object* o) {
    std::atomic_ref<std::uint32_t> refs(o->refs);
    if (refs.load(std::memory_order_relaxed) & Object::kShared)
      return refs.fetch_sub(1, std::memory_order_acq_rel) == (Object::kShared | 1);
    return --o->refs == 0;
  }

  static std::size_t classOf(std::size_t bytes);
  static constexpr std::size_t smallClassOf(std::size_t bytes) { return (bytes + 7) / 8 - 1; }
  static constexpr std::size_t classBytes(std::size_t cls) {
    return cls < kSmallClasses ? (cls + 1) * 8 : std::size_t(1) << (cls - kSmallClasses + 10);
  }
  // A raw block (the builder constructs the object): a small one from its class's free list in a
  // few instructions when the list has one (lists and the float structs of belief propagation
  // are made and dropped millions of times), else allocateSlow.
  void* allocate(std::size_t bytes);
  void* allocateSlow(std::size_t bytes);
  char* newSlab();  // a slab of kSlabBytes, aligned to its size, its owner not yet written
  ConsCell* newCell(TypeId listType);
  // A struct, array or set object (kind k) with room for `size` items, counted once; the builder
  // writes the items (a struct's field count is checked here).
  TupleObject* newTuple(TypeId type, TypeKind k, std::size_t size);
  // o's block (of `bytes`) goes back to the heap that allocated it.
  void recycle(Object* o, std::size_t bytes);
  Heap* ownerOf(const Object* o, std::size_t bytes) const;
  void pushRemote(Object* o, std::size_t cls);
  void drainRemote();
  static std::size_t objectBytes(TypeKind k, const Object* o);  // k: the kind of o's type
  void destroy(Object* o);  // count reached zero: release children, recycle the block
  // A dead cell's tail, whose count is read kDeferredTails deaths later, fetched meanwhile; returns
  // the tail whose turn it is (null while the ring fills).
  Object* deferTail(Object* tail);
  // Whether the items of a struct, array or set type hold no references (nothing to retain or
  // release: they copy as plain words). Worked out once per type.
  bool plainItems(TypeId t) {
    return t < plain_.size() && plain_[t] != kUnknown ? plain_[t] == kPlain : computePlainItems(t);
  }
  bool computePlainItems(TypeId t);
  // makePlainTuple's first call for a type, and every call for an array: checks the type (throws
  // where it is not a struct or array of plain items, or a struct's field count is not size) and
  // notes a plain struct's field count.
  Value* makePlainTupleChecked(TypeId type, std::uint32_t size, Value& result);
  TupleObject* newPlainTuple(TypeId type, std::uint32_t size);
  static constexpr std::uint32_t kNotPlainStruct = UINT32_MAX;
  static constexpr std::uint8_t kUnknown = 0, kPlain = 1, kHolds = 2;
  void shareObject(Object* o);

  const TypeTable& types_;
  NodeReferences* const nodes_;                   // fixed: destroy() decides from it whether to put tails off
  std::vector<std::uint8_t> plain_;               // per type: plainItems, once known
  std::vector<std::uint32_t> plainStructFields_;  // per type: the field count of a plain struct, once seen
  FreeBlock* free_[kSmallClasses + kLargeClasses] = {};
  std::vector<void*> slabs_;   // operator new's, the first kSlabsAlone
  std::vector<char*> chunks_;  // then kChunkBytes at a time, cut into slabs
  char* chunkNext_ = nullptr;
  char* chunkEnd_ = nullptr;
  std::vector<void*> large_;
  char* bump_ = nullptr;
  char* bumpEnd_ = nullptr;
  std::size_t live_ = 0, bytesInUse_ = 0, bytesReserved_ = 0;
  std::atomic<RemoteBlock*> remote_{nullptr};
  // The tails destroy() put off. Not used where node references are counted (a created node's
  // deletion waits for its count to drop: node_recycling.hpp), so that is never late.
  static constexpr std::size_t kDeferredTails = 16;
  Object* deferredTails_[kDeferredTails] = {};
  std::size_t nextDeferred_ = 0;
};

// Inline: the built-ins make their lists one cell at a time (ListBuilder; B2 belief-propagation:
// 65 million cells of float lists).
[[gnu::always_inline]] inline void* Heap::allocate(std::size_t bytes) {
  if (bytes <= kSmallMax) {
    const std::size_t cls = smallClassOf(bytes);
    if (FreeBlock* f = free_[cls]) {
      free_[cls] = f->next;
      // The block the next allocation of this class takes (it reads its link, then the caller
      // writes it) was freed long ago and is often cold: nine in ten of the samples of n-queens
      // 13's cons waited for it. Fetched now, it arrives while this one is used (cons went from
      // 8.7 % of the native run's samples to 2.9 %).
      __builtin_prefetch(f->next, 1);
      ++live_;
      bytesInUse_ += classBytes(cls);
      return f;
    }
  }
  return allocateSlow(bytes);
}

[[gnu::always_inline]] inline TupleObject* Heap::newPlainTuple(TypeId type, std::uint32_t size) {
  auto* t = new (allocate(sizeof(TupleObject) + sizeof(Value) * size)) TupleObject;
  t->refs = 1;
  t->type = type;
  t->size = t->capacity = size;
  return t;
}

[[gnu::always_inline]] inline ConsCell* Heap::newCell(TypeId listType) {
  auto* c = new (allocate(sizeof(ConsCell))) ConsCell;
  c->refs = 1;
  c->type = listType;
  return c;
}

}  // namespace meldvm
