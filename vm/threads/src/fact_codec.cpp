#include "fact_codec.hpp"

#include <cstring>
#include <string_view>

namespace meldvm::threads {

namespace {

void encodeValue(Words& out, const TypeTable& types, TypeId t, Value v) {
  switch (types.kind(t)) {
    case TypeKind::String: {
      const std::string_view s = stringOf(v);
      out.push_back(s.size());
      const std::size_t at = out.size();
      out.resize(at + (s.size() + 7) / 8, 0);
      std::memcpy(out.data() + at, s.data(), s.size());
      return;
    }
    case TypeKind::List: {
      const std::size_t countAt = out.size();
      out.push_back(0);
      std::uint64_t count = 0;
      for (Value l = v; !l.isNil(); l = listTail(l), ++count) encodeValue(out, types, types.element(t), listHead(l));
      out[countAt] = count;
      return;
    }
    case TypeKind::Struct: {
      const std::span<const Value> items = tupleItems(v);
      const std::span<const TypeId> fields = types.fields(t);
      out.push_back(items.size());
      for (std::size_t i = 0; i < items.size(); ++i) encodeValue(out, types, fields[i], items[i]);
      return;
    }
    case TypeKind::Array:
    case TypeKind::Set: {
      const std::span<const Value> items = tupleItems(v);
      out.push_back(items.size());
      for (Value item : items) encodeValue(out, types, types.element(t), item);
      return;
    }
    default:
      out.push_back(v.bits());
  }
}

// The value at words[pos], built in `heap` (a new reference for a boxed one). The items of a
// list or tuple wait on `scratch` (a stack shared by the nested calls: no allocation per value).
Value decodeValue(const Words& w, std::size_t& pos, Heap& heap, TypeId t, std::vector<Value>& scratch) {
  const TypeTable& types = heap.types();
  switch (types.kind(t)) {
    case TypeKind::String: {
      const std::size_t length = w[pos++];
      const Value s = heap.makeString({reinterpret_cast<const char*>(w.data() + pos), length});
      pos += (length + 7) / 8;
      return s;
    }
    case TypeKind::List: {
      const std::size_t count = w[pos++], base = scratch.size();
      for (std::size_t i = 0; i < count; ++i) {
        const Value item = decodeValue(w, pos, heap, types.element(t), scratch);
        scratch.push_back(item);
      }
      const std::span<const Value> items(scratch.data() + base, count);
      const Value list = heap.makeList(t, items);
      for (Value item : items) heap.release(types.element(t), item);
      scratch.resize(base);
      return list;
    }
    case TypeKind::Struct:
    case TypeKind::Array:
    case TypeKind::Set: {
      const std::size_t count = w[pos++], base = scratch.size();
      const bool isStruct = types.kind(t) == TypeKind::Struct;
      auto itemType = [&](std::size_t i) { return isStruct ? types.fields(t)[i] : types.element(t); };
      for (std::size_t i = 0; i < count; ++i) {
        const Value item = decodeValue(w, pos, heap, itemType(i), scratch);
        scratch.push_back(item);
      }
      const std::span<const Value> items(scratch.data() + base, count);
      const Value tuple = heap.makeTuple(t, items);
      for (std::size_t i = 0; i < count; ++i) heap.release(itemType(i), items[i]);
      scratch.resize(base);
      return tuple;
    }
    default:
      return Value::fromBits(w[pos++]);
  }
}

}  // namespace

void encodeArgs(Words& out, const PredicateDesc& p, const TypeTable& types, const Value* args) {
  for (std::uint32_t i = 0; i < p.arity(); ++i) encodeValue(out, types, p.fields[i], args[i]);
}

std::size_t decodeArgs(const Words& words, std::size_t pos, const PredicateDesc& p, Heap& heap, Value* args,
                       std::vector<Value>& scratch) {
  for (std::uint32_t i = 0; i < p.arity(); ++i) args[i] = decodeValue(words, pos, heap, p.fields[i], scratch);
  return pos;
}

void releaseArgs(const PredicateDesc& p, Heap& heap, const Value* args) {
  for (std::uint32_t i = 0; i < p.arity(); ++i) heap.release(p.fields[i], args[i]);
}

}  // namespace meldvm::threads
