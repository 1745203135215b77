#include "meldvm/heap.hpp"

#include <bit>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "meldvm/value_ops.hpp"

namespace meldvm {

namespace {

// Calls visit(type, value) for each item of o (a list cell's head, a tuple's items) and returns
// its rest (a list cell's tail, else null): destroy() and share() walk lists along it iteratively.
template <class Visit>
Object* visitItems(const TypeTable& types, Object* o, Visit&& visit) {
  const TypeId t = o->type;
  switch (types.kind(t)) {
    case TypeKind::List: {
      auto* c = static_cast<ConsCell*>(o);
      visit(types.element(t), c->head);
      return c->tail;
    }
    case TypeKind::Struct: {
      auto* tu = static_cast<TupleObject*>(o);
      const auto fieldTypes = types.fields(t);
      for (std::uint32_t i = 0; i < tu->size; ++i) visit(fieldTypes[i], tu->items()[i]);
      return nullptr;
    }
    case TypeKind::Array:
    case TypeKind::Set: {
      auto* tu = static_cast<TupleObject*>(o);
      for (std::uint32_t i = 0; i < tu->size; ++i) visit(types.element(t), tu->items()[i]);
      return nullptr;
    }
    default:
      return nullptr;
  }
}

}  // namespace

Heap::~Heap() {
  // Objects still referenced die with the heap: their memory is the slabs themselves. (Heaps
  // that shared objects with each other go together, after every reference is released:
  // threads/README.md.)
  for (void* p : slabs_) ::operator delete(p, std::align_val_t(kSlabBytes));
  for (char* c : chunks_) support::freeLarge(c, kChunkBytes);
  for (void* p : large_) ::operator delete(p);
}

std::size_t Heap::classOf(std::size_t bytes) {
  if (bytes <= kSmallMax) return smallClassOf(bytes);
  const std::size_t cls = kSmallClasses + std::size_t(std::bit_width(bytes - 1)) - 10;
  if (cls >= kSmallClasses + kLargeClasses) throw std::length_error("meldvm: object too large");
  return cls;
}

void* Heap::allocateSlow(std::size_t bytes) {
  const std::size_t cls = classOf(bytes);
  const std::size_t size = classBytes(cls);
  void* p;
  if (!free_[cls] && remote_.load(std::memory_order_relaxed)) drainRemote();
  if (FreeBlock* f = free_[cls]) {
    free_[cls] = f->next;
    p = f;
  } else if (cls < kSmallClasses) {
    if (std::size_t(bumpEnd_ - bump_) < size) {
      // The unused end of the previous slab is abandoned; at most kSmallMax bytes per slab. A
      // slab is aligned to its size and starts with its owner, so a block's owner is found from
      // its address alone.
      char* slab = newSlab();
      *reinterpret_cast<Heap**>(slab) = this;
      bump_ = slab + kOwnerBytes;
      bumpEnd_ = slab + kSlabBytes;
    }
    p = bump_;
    bump_ += size;
  } else {
    char* block = static_cast<char*>(::operator new(size + kOwnerBytes));
    *reinterpret_cast<Heap**>(block) = this;
    large_.push_back(block);
    p = block + kOwnerBytes;
    bytesReserved_ += size + kOwnerBytes;
  }
  ++live_;
  bytesInUse_ += size;
  return p;
}

[[gnu::always_inline]] inline void Heap::recycle(Object* o, std::size_t bytes) {
  const std::size_t cls = bytes <= kSmallMax ? smallClassOf(bytes) : classOf(bytes);
  if (isShared(o)) {  // freed by whichever thread dropped the last reference
    if (Heap* owner = ownerOf(o, bytes); owner != this) return owner->pushRemote(o, cls);
  }
  --live_;
  bytesInUse_ -= classBytes(cls);
  free_[cls] = new (static_cast<void*>(o)) FreeBlock{free_[cls]};
}

char* Heap::newSlab() {
  if (slabs_.size() < kSlabsAlone) {
    char* slab = static_cast<char*>(::operator new(kSlabBytes, std::align_val_t(kSlabBytes)));
    slabs_.push_back(slab);
    bytesReserved_ += kSlabBytes;
    support::prefault(slab, kSlabBytes);  // its blocks are handed out one after the other
    return slab;
  }
  if (chunkNext_ == chunkEnd_) {  // a chunk is aligned to 2 MiB: its slabs to their size
    static_assert(kChunkBytes % kSlabBytes == 0);
    chunkNext_ = static_cast<char*>(support::allocateLarge(kChunkBytes));
    chunkEnd_ = chunkNext_ + kChunkBytes;
    chunks_.push_back(chunkNext_);
    bytesReserved_ += kChunkBytes;
  }
  char* slab = chunkNext_;
  chunkNext_ += kSlabBytes;
  return slab;
}

Heap* Heap::ownerOf(const Object* o, std::size_t bytes) const {
  const char* at =
      bytes <= kSmallMax
          ? reinterpret_cast<const char*>(reinterpret_cast<std::uintptr_t>(o) & ~(kSlabBytes - 1))
          : reinterpret_cast<const char*>(o) - kOwnerBytes;
  return *reinterpret_cast<Heap* const*>(at);
}

void Heap::pushRemote(Object* o, std::size_t cls) {
  static_assert(sizeof(RemoteBlock) <= 16, "the smallest block holds a RemoteBlock");
  auto* r = new (static_cast<void*>(o)) RemoteBlock{remote_.load(std::memory_order_relaxed), cls};
  while (!remote_.compare_exchange_weak(r->next, r, std::memory_order_release, std::memory_order_relaxed)) {
  }
}

void Heap::drainRemote() {
  for (RemoteBlock* r = remote_.exchange(nullptr, std::memory_order_acquire); r;) {
    RemoteBlock* next = r->next;
    const std::size_t cls = r->cls;
    --live_;
    bytesInUse_ -= classBytes(cls);
    free_[cls] = new (static_cast<void*>(r)) FreeBlock{free_[cls]};
    r = next;
  }
}

void Heap::share(TypeId t, Value v) {
  if (types_.boxed(t) && !v.isNil()) shareObject(v.asObject());
}

// The walk of a moving node's list usually ends at its second cell (the tails its siblings share
// were shared by the first of them), so those are the two fetched: the first cell sixteen objects
// on, the second eight on (its first cell arrived meanwhile). Sharing n-queens 13's moved facts
// one by one waited for both cells each time: 6 % of a -j 2 run, the other thread idle meanwhile.
namespace {
constexpr std::size_t kShareAhead = 16, kShareSecondAhead = 8;
}

void Heap::shareAll(std::span<Object* const> objects) {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (i + kShareAhead < objects.size()) __builtin_prefetch(objects[i + kShareAhead]);
    if (i + kShareSecondAhead < objects.size()) {
      const Object* o = objects[i + kShareSecondAhead];
      if (types_.kind(o->type) == TypeKind::List)
        if (const ConsCell* tail = static_cast<const ConsCell*>(o)->tail) __builtin_prefetch(tail);
    }
    shareObject(objects[i]);
  }
}

void Heap::shareObject(Object* o) {
  // What is shared already reaches only shared objects: the walk stops there.
  while (o && !isShared(o)) {
    o->refs |= Object::kShared;
    o = visitItems(types_, o, [&](TypeId t, Value v) { share(t, v); });
  }
}

inline std::size_t Heap::objectBytes(TypeKind k, const Object* o) {
  switch (k) {
    case TypeKind::String:
      return sizeof(StringObject) + static_cast<const StringObject*>(o)->length;
    case TypeKind::List:
      return sizeof(ConsCell);
    default:
      return sizeof(TupleObject) + sizeof(Value) * static_cast<const TupleObject*>(o)->capacity;
  }
}

Value Heap::makeString(std::string_view s) {
  if (s.size() > UINT32_MAX - 64) throw std::length_error("meldvm: string too long");
  auto* str = new (allocate(sizeof(StringObject) + s.size())) StringObject;
  str->refs = 1;
  str->type = TypeTable::kString;
  str->length = std::uint32_t(s.size());
  if (!s.empty()) std::memcpy(reinterpret_cast<char*>(str + 1), s.data(), s.size());
  return Value::fromObject(str);
}

Value Heap::cons(TypeId listType, Value head, Value tail) {
  retainStored(types_.element(listType), head);
  retain(listType, tail);
  auto* c = newCell(listType);
  c->head = head;
  c->tail = static_cast<ConsCell*>(tail.asObject());
  return Value::fromObject(c);
}

Value Heap::makeList(TypeId listType, std::span<const Value> items, Value tail) {
  const TypeId elem = types_.element(listType);
  retain(listType, tail);
  auto* list = static_cast<ConsCell*>(
      tail.asObject());  // built from the back; each new cell takes over the reference to the rest
  for (std::size_t i = items.size(); i-- > 0;) {
    retainStored(elem, items[i]);
    auto* c = newCell(listType);
    c->head = items[i];
    c->tail = list;
    list = c;
  }
  return Value::fromObject(list);
}

[[gnu::always_inline]] inline TupleObject* Heap::newTuple(TypeId type, TypeKind k, std::size_t size) {
  if (k == TypeKind::Struct && size != types_.fields(type).size())
    throw std::invalid_argument("meldvm: struct " + types_.name(type) + " built with a wrong field count");
  return newPlainTuple(type, std::uint32_t(size));
}

Value Heap::makeTuple(TypeId type, std::span<const Value> items) {
  const TypeKind k = types_.kind(type);
  if (k != TypeKind::Struct && k != TypeKind::Array && k != TypeKind::Set)
    throw std::invalid_argument("meldvm: makeTuple needs a struct, array or set type");
  TupleObject* t = newTuple(type, k, items.size());
  auto* out = reinterpret_cast<Value*>(t + 1);
  if (k != TypeKind::Set && plainItems(type)) {  // plain words: nothing to retain
    static_assert(std::is_trivially_copyable_v<Value>);
    if (!items.empty()) std::memcpy(static_cast<void*>(out), items.data(), sizeof(Value) * items.size());
    return Value::fromObject(t);
  }
  std::uint32_t n = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const TypeId it = k == TypeKind::Struct ? types_.fields(type)[i] : types_.element(type);
    if (k == TypeKind::Set) {
      bool seen = false;
      for (std::uint32_t j = 0; j < n && !seen; ++j) seen = valuesEqual(types_, it, out[j], items[i]);
      if (seen) continue;
    }
    retainStored(it, items[i]);
    new (out + n++) Value(items[i]);
  }
  for (std::uint32_t j = n; j < items.size(); ++j) new (out + j) Value();  // dropped set duplicates
  t->size = n;
  return Value::fromObject(t);
}

Value* Heap::makePlainTupleChecked(TypeId type, std::uint32_t size, Value& result) {
  const TypeKind k = types_.kind(type);
  if ((k != TypeKind::Struct && k != TypeKind::Array) || !plainItems(type))
    throw std::invalid_argument("meldvm: makePlainTuple needs a struct or array of unboxed items");
  TupleObject* t = newTuple(type, k, size);  // checks a struct's field count
  if (k == TypeKind::Struct) {
    if (plainStructFields_.size() <= type) plainStructFields_.resize(types_.size(), kNotPlainStruct);
    plainStructFields_[type] = size;
  }
  result = Value::fromObject(t);
  return reinterpret_cast<Value*>(t + 1);
}

bool Heap::computePlainItems(TypeId t) {
  if (plain_.size() < types_.size()) plain_.resize(types_.size(), kUnknown);
  bool plain = true;
  if (types_.kind(t) == TypeKind::Struct) {
    for (TypeId f : types_.fields(t)) plain = plain && !holdsReferences(f);
  } else {
    plain = !holdsReferences(types_.element(t));
  }
  plain_[t] = plain ? kPlain : kHolds;
  return plain;
}

inline Object* Heap::deferTail(Object* tail) {
  __builtin_prefetch(tail, 1);
  Object* due = std::exchange(deferredTails_[nextDeferred_], tail);
  nextDeferred_ = (nextDeferred_ + 1) % kDeferredTails;
  return due;
}

// When a list's last reference goes, its cells die one after the other, and each death reads the
// count of the next cell: consed long before, at another node, and cold by now. n-queens 13 spent a
// sixth of its native run waiting there, one cell at a time. So a dead cell's tail joins a ring of
// kDeferredTails and its count is read when the ring comes round to it, fetched meanwhile; the
// waits of many lists overlap. Only the moment of freeing moves: a count decides nothing but when
// its block is freed (native code's inline releases read counts too, and a count that stays
// higher for a while only makes them leave the last release to the heap later); liveObjects()
// and bytesInUse() drop the ring first.
void Heap::destroy(Object* o) {
  // A plain struct (belief propagation's float structs: 3.6 million die in belief-propagation-50)
  // holds nothing to release and has no tail: its block goes straight back.
  if (o->type < plainStructFields_.size() && plainStructFields_[o->type] != kNotPlainStruct) {
    recycle(o, objectBytes(TypeKind::Struct, o));
    return;
  }
  // Iterative along list tails, so that releasing a long list cannot overflow the stack.
  while (o) {
    const TypeKind k = types_.kind(o->type);
    Object* rest = nullptr;
    if (k == TypeKind::List) {
      // A cell apart: B2 belief-propagation frees some 80 million cells of float lists, whose
      // heads hold nothing to release (plainItems, known per type).
      auto* c = static_cast<ConsCell*>(o);
      if (!plainItems(c->type)) releaseStored(types_.element(c->type), c->head);
      rest = c->tail;
      recycle(o, sizeof(ConsCell));
    } else {
      if (k != TypeKind::String && !plainItems(o->type))
        rest = visitItems(types_, o, [&](TypeId t, Value v) { releaseStored(t, v); });
      recycle(o, objectBytes(k, o));
    }
    if (rest && !nodes_) rest = deferTail(rest);  // (not where node references are counted)
    o = rest && dropReference(rest) ? rest : nullptr;
  }
}

void Heap::dropDeferredTails() {
  // A tail dropped here may die and put off its own tail: round again until the ring is empty.
  for (bool dropped = true; dropped;) {
    dropped = false;
    for (Object*& slot : deferredTails_)
      if (Object* o = std::exchange(slot, nullptr)) {
        dropped = true;
        if (dropReference(o)) destroy(o);
      }
  }
}

}  // namespace meldvm
