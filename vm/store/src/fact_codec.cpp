#include "meldvm/fact_codec.hpp"

#include <cstring>

namespace meldvm {

namespace {

template <class T>
void put(std::vector<std::uint8_t>& out, T v) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // the simulator and its blocks share one byte order
  out.insert(out.end(), b, b + sizeof(T));
}

void encodeValue(std::vector<std::uint8_t>& out, const TypeTable& types, TypeId t, Value v) {
  switch (types.kind(t)) {
    case TypeKind::Int:
      put<std::int32_t>(out, v.asInt());
      break;
    case TypeKind::Float:
      put<double>(out, v.asFloat());
      break;
    case TypeKind::Bool:
      put<std::uint8_t>(out, v.asBool());
      break;
    case TypeKind::Node:
    case TypeKind::Thread:
      put<std::uint32_t>(out, std::uint32_t(v.bits()));
      break;
    case TypeKind::String: {
      const std::string_view s = stringOf(v);
      put<std::uint32_t>(out, std::uint32_t(s.size()));
      out.insert(out.end(), s.begin(), s.end());
      break;
    }
    case TypeKind::List: {
      std::uint32_t n = 0;
      for (Value l = v; !l.isNil(); l = listTail(l)) ++n;
      put<std::uint32_t>(out, n);
      for (Value l = v; !l.isNil(); l = listTail(l)) encodeValue(out, types, types.element(t), listHead(l));
      break;
    }
    case TypeKind::Struct: {
      const auto items = tupleItems(v);
      const auto fields = types.fields(t);
      for (std::size_t i = 0; i < items.size(); ++i) encodeValue(out, types, fields[i], items[i]);
      break;
    }
    case TypeKind::Array:
    case TypeKind::Set: {
      const auto items = tupleItems(v);
      put<std::uint32_t>(out, std::uint32_t(items.size()));
      for (Value x : items) encodeValue(out, types, types.element(t), x);
      break;
    }
  }
}

// Decoded items of lists, structs, arrays and sets wait on one stack (the caller's reusable
// vector), so decoding allocates nothing but the values themselves once the stack has grown.
class Reader {
 public:
  Reader(const std::uint8_t* d, std::size_t n, const TypeTable& types, Heap& heap, std::vector<Value>& stack)
      : d_(d), n_(n), types_(types), heap_(heap), stack_(stack) {}
  template <class T>
  T get() {
    if (n_ - at_ < sizeof(T)) throw FactCodecError("truncated fact message");
    T v;
    std::memcpy(&v, d_ + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::uint32_t count() {  // every item takes at least one byte
    const std::uint32_t c = get<std::uint32_t>();
    if (c > n_ - at_) throw FactCodecError("bad count in fact message");
    return c;
  }
  Value value(TypeId t);  // an owned reference
  bool done() const { return at_ == n_; }

 private:
  // Decodes `count` items onto the stack, builds the object with `make`, releases the items.
  template <class ItemType, class Make>
  Value items(std::uint32_t count, ItemType itemType, Make make) {
    const std::size_t base = stack_.size();
    try {
      for (std::uint32_t i = 0; i < count; ++i) stack_.push_back(value(itemType(i)));
    } catch (...) {
      for (std::size_t i = base; i < stack_.size(); ++i)
        heap_.release(itemType(std::uint32_t(i - base)), stack_[i]);
      stack_.resize(base);
      throw;
    }
    auto releaseItems = [&] {
      for (std::uint32_t i = 0; i < count; ++i) heap_.release(itemType(i), stack_[base + i]);
      stack_.resize(base);
    };
    Value v;
    try {
      v = make(std::span<const Value>(stack_.data() + base, count));
    } catch (...) {
      releaseItems();
      throw;
    }
    releaseItems();
    return v;
  }

  const std::uint8_t* d_;
  std::size_t n_, at_ = 0;
  const TypeTable& types_;
  Heap& heap_;
  std::vector<Value>& stack_;
};

Value Reader::value(TypeId t) {
  switch (types_.kind(t)) {
    case TypeKind::Int:
      return Value::fromInt(get<std::int32_t>());
    case TypeKind::Float:
      return Value::fromFloat(get<double>());
    case TypeKind::Bool:
      return Value::fromBool(get<std::uint8_t>() != 0);
    case TypeKind::Node:
      return Value::fromNode(get<std::uint32_t>());
    case TypeKind::Thread:
      return Value::fromThread(get<std::uint32_t>());
    case TypeKind::String: {
      const std::uint32_t len = count();
      const Value s = heap_.makeString({reinterpret_cast<const char*>(d_ + at_), len});
      at_ += len;
      return s;
    }
    case TypeKind::List: {
      const TypeId e = types_.element(t);
      return items(
          count(), [e](std::uint32_t) { return e; },
          [&](std::span<const Value> v) { return heap_.makeList(t, v); });
    }
    case TypeKind::Struct: {
      const auto fields = types_.fields(t);
      return items(
          std::uint32_t(fields.size()), [fields](std::uint32_t i) { return fields[i]; },
          [&](std::span<const Value> v) { return heap_.makeTuple(t, v); });
    }
    case TypeKind::Array:
    case TypeKind::Set: {
      const TypeId e = types_.element(t);
      return items(
          count(), [e](std::uint32_t) { return e; },
          [&](std::span<const Value> v) { return heap_.makeTuple(t, v); });
    }
  }
  throw FactCodecError("bad type in fact message");
}

}  // namespace

void encodeFact(std::vector<std::uint8_t>& out, const PredicateTable& preds, PredId p, const Value* args,
                bool negative) {
  put<std::uint16_t>(out, std::uint16_t(p));
  put<std::uint8_t>(out, negative ? 1 : 0);
  const PredicateDesc& d = preds[p];
  for (std::uint32_t i = 0; i < d.arity(); ++i) encodeValue(out, preds.types(), d.fields[i], args[i]);
}

void decodeFact(const std::uint8_t* data, std::size_t size, const PredicateTable& preds, Heap& heap,
                DecodedFact& fact) {
  Reader r(data, size, preds.types(), heap, fact.stack);
  fact.pred = r.get<std::uint16_t>();
  if (fact.pred >= preds.size()) throw FactCodecError("unknown predicate in fact message");
  const std::uint8_t flags = r.get<std::uint8_t>();
  if (flags > 1) throw FactCodecError("bad flags in fact message");
  fact.negative = flags == 1;
  const PredicateDesc& d = preds[fact.pred];
  fact.args.clear();
  try {
    for (std::uint32_t i = 0; i < d.arity(); ++i) fact.args.push_back(r.value(d.fields[i]));
    if (!r.done()) throw FactCodecError("trailing bytes in fact message");
  } catch (...) {
    for (std::size_t i = 0; i < fact.args.size(); ++i) heap.release(d.fields[i], fact.args[i]);
    fact.args.clear();
    throw;
  }
}

}  // namespace meldvm
