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

class Reader {
 public:
  Reader(const std::uint8_t* d, std::size_t n, const TypeTable& types, Heap& heap)
      : d_(d), n_(n), types_(types), heap_(heap) {}
  template <class T>
  T get() {
    if (n_ - at_ < sizeof(T)) throw FactCodecError("truncated fact message");
    T v;
    std::memcpy(&v, d_ + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::uint32_t count(std::size_t minItemBytes) {
    const std::uint32_t c = get<std::uint32_t>();
    if (minItemBytes && c > (n_ - at_) / minItemBytes) throw FactCodecError("bad count in fact message");
    return c;
  }
  Value value(TypeId t);  // an owned reference
  bool done() const { return at_ == n_; }

 private:
  const std::uint8_t* d_;
  std::size_t n_, at_ = 0;
  const TypeTable& types_;
  Heap& heap_;
  std::vector<Value> items_;
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
      const std::uint32_t len = count(1);
      const Value s = heap_.makeString({reinterpret_cast<const char*>(d_ + at_), len});
      at_ += len;
      return s;
    }
    case TypeKind::List: {
      const std::uint32_t c = count(1);
      std::vector<Value> items;
      items.reserve(c);
      for (std::uint32_t i = 0; i < c; ++i) items.push_back(value(types_.element(t)));
      const Value l = heap_.makeList(t, items);
      for (Value x : items) heap_.release(types_.element(t), x);
      return l;
    }
    case TypeKind::Struct:
    case TypeKind::Array:
    case TypeKind::Set: {
      std::vector<TypeId> itemTypes;
      if (types_.kind(t) == TypeKind::Struct) {
        const auto f = types_.fields(t);
        itemTypes.assign(f.begin(), f.end());
      } else {
        itemTypes.assign(count(1), types_.element(t));
      }
      std::vector<Value> items;
      for (TypeId it : itemTypes) items.push_back(value(it));
      const Value v = heap_.makeTuple(t, items);
      for (std::size_t i = 0; i < items.size(); ++i) heap_.release(itemTypes[i], items[i]);
      return v;
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
  Reader r(data, size, preds.types(), heap);
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
