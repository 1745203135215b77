#include "meldvm/value_ops.hpp"

#include <cmath>
#include <cstdio>

#include "meldvm/heap.hpp"

namespace meldvm {

namespace {

bool floatsEqual(double a, double b) {
  return a == b ||
         (std::isnan(a) && std::isnan(b) && Value::fromFloat(a).bits() == Value::fromFloat(b).bits());
}

std::uint64_t floatHash(double d) {
  if (d == 0.0) d = 0.0;  // -0.0 and 0.0 are equal, so they must hash alike
  return Value::fromFloat(d).bits();
}

template <class T>
int threeWay(T a, T b) {
  return a < b ? -1 : (b < a ? 1 : 0);
}

}  // namespace

bool valuesEqual(const TypeTable& types, TypeId t, Value a, Value b) {
  switch (types.kind(t)) {
    case TypeKind::Float:
      return floatsEqual(a.asFloat(), b.asFloat());
    case TypeKind::Int:
    case TypeKind::Bool:
    case TypeKind::Node:
    case TypeKind::Thread:
      return a.bits() == b.bits();
    case TypeKind::String:
      return a.bits() == b.bits() || stringOf(a) == stringOf(b);
    case TypeKind::List: {
      const TypeId elem = types.element(t);
      while (!a.isNil() && !b.isNil()) {
        if (a.bits() == b.bits()) return true;  // shared tail
        if (!valuesEqual(types, elem, listHead(a), listHead(b))) return false;
        a = listTail(a);
        b = listTail(b);
      }
      return a.isNil() && b.isNil();
    }
    case TypeKind::Struct:
    case TypeKind::Array:
    case TypeKind::Set: {
      if (a.bits() == b.bits()) return true;
      const auto x = tupleItems(a), y = tupleItems(b);
      if (x.size() != y.size()) return false;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const TypeId it = types.kind(t) == TypeKind::Struct ? types.fields(t)[i] : types.element(t);
        if (!valuesEqual(types, it, x[i], y[i])) return false;
      }
      return true;
    }
  }
  return false;
}

std::uint64_t hashValue(const TypeTable& types, TypeId t, Value v) {
  switch (types.kind(t)) {
    case TypeKind::Float:
      return mixHash(1, floatHash(v.asFloat()));
    case TypeKind::Int:
    case TypeKind::Bool:
    case TypeKind::Node:
    case TypeKind::Thread:
      return hashIntegerLike(v);
    case TypeKind::String: {
      std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a
      for (unsigned char c : stringOf(v)) h = (h ^ c) * 0x100000001b3ull;
      return mixHash(3, h);
    }
    case TypeKind::List: {
      std::uint64_t h = 4;
      for (; !v.isNil(); v = listTail(v)) h = mixHash(h, hashValue(types, types.element(t), listHead(v)));
      return h;
    }
    case TypeKind::Struct:
    case TypeKind::Array:
    case TypeKind::Set: {
      std::uint64_t h = 5;
      const auto items = tupleItems(v);
      for (std::size_t i = 0; i < items.size(); ++i) {
        const TypeId it = types.kind(t) == TypeKind::Struct ? types.fields(t)[i] : types.element(t);
        h = mixHash(h, hashValue(types, it, items[i]));
      }
      return h;
    }
  }
  return 0;
}

int compareValues(const TypeTable& types, TypeId t, Value a, Value b) {
  switch (types.kind(t)) {
    case TypeKind::Int:
      return threeWay(a.asInt(), b.asInt());
    case TypeKind::Float: {
      const double x = a.asFloat(), y = b.asFloat();
      if (std::isnan(x) || std::isnan(y)) return threeWay(std::isnan(x), std::isnan(y));
      return threeWay(x, y);
    }
    case TypeKind::Bool:
      return threeWay(a.asBool(), b.asBool());
    case TypeKind::Node:
      return threeWay(a.asNode(), b.asNode());
    case TypeKind::Thread:
      return threeWay(a.asThread(), b.asThread());
    case TypeKind::String:
      return threeWay(stringOf(a).compare(stringOf(b)), 0);
    case TypeKind::List: {
      const TypeId elem = types.element(t);
      for (; !a.isNil() && !b.isNil(); a = listTail(a), b = listTail(b))
        if (const int c = compareValues(types, elem, listHead(a), listHead(b))) return c;
      return threeWay(!a.isNil(), !b.isNil());
    }
    case TypeKind::Struct:
    case TypeKind::Array:
    case TypeKind::Set: {
      const auto x = tupleItems(a), y = tupleItems(b);
      for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
        const TypeId it = types.kind(t) == TypeKind::Struct ? types.fields(t)[i] : types.element(t);
        if (const int c = compareValues(types, it, x[i], y[i])) return c;
      }
      return threeWay(x.size(), y.size());
    }
  }
  return 0;
}

void appendFloat(std::string& out, double d) {
  // The established VM prints with an ostream at precision 5, which libstdc++ implements with
  // printf("%.5g") — including "inf", "-inf", "nan" and "-nan".
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, "%.5g", d);
  out.append(buf, std::size_t(n));
}

void appendValue(std::string& out, const TypeTable& types, TypeId t, Value v) {
  switch (types.kind(t)) {
    case TypeKind::Int:
      out += std::to_string(v.asInt());
      return;
    case TypeKind::Float:
      appendFloat(out, v.asFloat());
      return;
    case TypeKind::Bool:
      out += v.asBool() ? "true" : "false";
      return;
    case TypeKind::Node:
      out += '@';
      out += std::to_string(v.asNode());
      return;
    case TypeKind::Thread:
      out += "#T";
      out += std::to_string(v.asThread());
      return;
    case TypeKind::String:
      out += '"';
      out += stringOf(v);  // raw: the established VM escapes nothing
      out += '"';
      return;
    case TypeKind::List:
      // Every element, comma without a space (§8: the HEAD VM's "..." truncation is not wanted).
      out += '[';
      for (Value c = v; !c.isNil(); c = listTail(c)) {
        if (c.bits() != v.bits()) out += ',';
        appendValue(out, types, types.element(t), listHead(c));
      }
      out += ']';
      return;
    case TypeKind::Struct:
    case TypeKind::Array:
    case TypeKind::Set: {
      const TypeKind k = types.kind(t);
      out += k == TypeKind::Struct ? ":(" : (k == TypeKind::Array ? "#[" : "{");
      const auto items = tupleItems(v);
      for (std::size_t i = 0; i < items.size(); ++i) {
        if (i) out += ", ";
        appendValue(out, types, k == TypeKind::Struct ? types.fields(t)[i] : types.element(t), items[i]);
      }
      out += k == TypeKind::Struct ? ")" : (k == TypeKind::Array ? "]" : "}");
      return;
    }
  }
}

}  // namespace meldvm
