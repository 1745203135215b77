#include "meldvm/heap.hpp"

#include <bit>
#include <cstring>
#include <new>
#include <stdexcept>

#include "meldvm/value_ops.hpp"

namespace meldvm {

Heap::~Heap() {
  // Objects still referenced die with the heap: their memory is the slabs themselves.
  for (void* p : slabs_) ::operator delete(p);
  for (void* p : large_) ::operator delete(p);
}

std::size_t Heap::classOf(std::size_t bytes) {
  bytes = (bytes + 7) & ~std::size_t(7);
  if (bytes <= kSmallMax) return bytes / 8 - 1;
  const std::size_t cls = kSmallClasses + std::size_t(std::bit_width(bytes - 1)) - 10;
  if (cls >= kSmallClasses + kLargeClasses) throw std::length_error("meldvm: object too large");
  return cls;
}

std::size_t Heap::classBytes(std::size_t cls) {
  return cls < kSmallClasses ? (cls + 1) * 8 : std::size_t(1) << (cls - kSmallClasses + 10);
}

void* Heap::allocate(std::size_t bytes) {
  const std::size_t cls = classOf(bytes);
  const std::size_t size = classBytes(cls);
  void* p;
  if (FreeBlock* f = free_[cls]) {
    free_[cls] = f->next;
    p = f;
  } else if (cls < kSmallClasses) {
    if (std::size_t(bumpEnd_ - bump_) < size) {
      // The unused end of the previous slab is abandoned; at most kSmallMax bytes per slab.
      bump_ = static_cast<char*>(::operator new(kSlabBytes));
      bumpEnd_ = bump_ + kSlabBytes;
      slabs_.push_back(bump_);
      bytesReserved_ += kSlabBytes;
    }
    p = bump_;
    bump_ += size;
  } else {
    p = ::operator new(size);
    large_.push_back(p);
    bytesReserved_ += size;
  }
  ++live_;
  bytesInUse_ += size;
  return p;
}

void Heap::deallocate(Object* o, std::size_t bytes) {
  const std::size_t cls = classOf(bytes);
  --live_;
  bytesInUse_ -= classBytes(cls);
  auto* f = new (static_cast<void*>(o)) FreeBlock{free_[cls]};
  free_[cls] = f;
}

std::size_t Heap::objectBytes(const Object* o) const {
  switch (types_.kind(o->type)) {
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

ConsCell* Heap::newCell(TypeId listType) {
  auto* c = new (allocate(sizeof(ConsCell))) ConsCell;
  c->refs = 1;
  c->type = listType;
  return c;
}

Value Heap::cons(TypeId listType, Value head, Value tail) {
  retain(types_.element(listType), head);
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
    retain(elem, items[i]);
    auto* c = newCell(listType);
    c->head = items[i];
    c->tail = list;
    list = c;
  }
  return Value::fromObject(list);
}

Value Heap::makeTuple(TypeId type, std::span<const Value> items) {
  const TypeKind k = types_.kind(type);
  if (k != TypeKind::Struct && k != TypeKind::Array && k != TypeKind::Set)
    throw std::invalid_argument("meldvm: makeTuple needs a struct, array or set type");
  if (k == TypeKind::Struct && items.size() != types_.fields(type).size())
    throw std::invalid_argument("meldvm: struct " + types_.name(type) + " built with a wrong field count");
  auto* t = new (allocate(sizeof(TupleObject) + sizeof(Value) * items.size())) TupleObject;
  t->refs = 1;
  t->type = type;
  auto* out = reinterpret_cast<Value*>(t + 1);
  std::uint32_t n = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const TypeId it = k == TypeKind::Struct ? types_.fields(type)[i] : types_.element(type);
    if (k == TypeKind::Set) {
      bool seen = false;
      for (std::uint32_t j = 0; j < n && !seen; ++j) seen = valuesEqual(types_, it, out[j], items[i]);
      if (seen) continue;
    }
    retain(it, items[i]);
    new (out + n++) Value(items[i]);
  }
  for (std::uint32_t j = n; j < items.size(); ++j) new (out + j) Value();  // dropped set duplicates
  t->size = n;
  t->capacity = std::uint32_t(items.size());
  return Value::fromObject(t);
}

void Heap::destroy(Object* o) {
  // Iterative along list tails, so that releasing a long list cannot overflow the stack.
  while (o) {
    Object* next = nullptr;
    const TypeId t = o->type;
    switch (types_.kind(t)) {
      case TypeKind::List: {
        auto* c = static_cast<ConsCell*>(o);
        release(types_.element(t), c->head);
        if (c->tail && --c->tail->refs == 0) next = c->tail;
        break;
      }
      case TypeKind::Struct: {
        auto* tu = static_cast<TupleObject*>(o);
        const auto fieldTypes = types_.fields(t);
        for (std::uint32_t i = 0; i < tu->size; ++i) release(fieldTypes[i], tu->items()[i]);
        break;
      }
      case TypeKind::Array:
      case TypeKind::Set: {
        auto* tu = static_cast<TupleObject*>(o);
        for (std::uint32_t i = 0; i < tu->size; ++i) release(types_.element(t), tu->items()[i]);
        break;
      }
      default:
        break;
    }
    deallocate(o, objectBytes(o));
    o = next;
  }
}

}  // namespace meldvm
