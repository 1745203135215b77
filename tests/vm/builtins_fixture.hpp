// Shared set-up of the built-in function tests: a type table, a heap, a BuiltinContext, builders
// for argument values, a call helper that keeps the results it receives and releases them (and
// the arguments it built) at the end, and a leak check: when the fixture goes, the heap must be
// empty again.
#pragma once

#include <boost/test/unit_test.hpp>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "meldvm/builtins.hpp"
#include "meldvm/heap.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value_ops.hpp"

namespace bitest {

using namespace meldvm;

struct Fix {
  TypeTable types;
  Heap heap{types};
  BuiltinContext ctx{heap};
  TypeId tInt = TypeTable::kInt, tFloat = TypeTable::kFloat, tBool = TypeTable::kBool,
         tNode = TypeTable::kNode, tThread = TypeTable::kThread, tString = TypeTable::kString;
  TypeId tLI = types.list(tInt), tLF = types.list(tFloat), tLN = types.list(tNode), tLS = types.list(tString),
         tLLI = types.list(tLI);
  TypeId tAI = types.array(tInt), tAS = types.array(tString), tSI = types.set(tInt);
  std::vector<std::pair<TypeId, Value>> owned;

  ~Fix() {
    for (auto it = owned.rbegin(); it != owned.rend(); ++it) heap.release(it->first, it->second);
    BOOST_CHECK_EQUAL(heap.liveObjects(), 0u);
  }

  Value keep(TypeId t, Value v) {
    if (types.boxed(t) && !v.isNil()) owned.emplace_back(t, v);
    return v;
  }
  Value ints(std::initializer_list<std::int32_t> xs) {
    std::vector<Value> v;
    for (auto x : xs) v.push_back(Value::fromInt(x));
    return keep(tLI, heap.makeList(tLI, v));
  }
  Value floats(std::initializer_list<double> xs) {
    std::vector<Value> v;
    for (auto x : xs) v.push_back(Value::fromFloat(x));
    return keep(tLF, heap.makeList(tLF, v));
  }
  Value nodes(std::initializer_list<NodeId> xs) {
    std::vector<Value> v;
    for (auto x : xs) v.push_back(Value::fromNode(x));
    return keep(tLN, heap.makeList(tLN, v));
  }
  Value str(std::string_view s) { return keep(tString, heap.makeString(s)); }
  Value strs(std::initializer_list<const char*> xs) {
    std::vector<Value> v;
    for (auto x : xs) v.push_back(str(x));
    return keep(tLS, heap.makeList(tLS, v));
  }
  Value tuple(TypeId t, std::vector<Value> items) { return keep(t, heap.makeTuple(t, items)); }
  TypeId floatStruct(std::size_t n) { return types.structOf(std::vector<TypeId>(n, tFloat)); }
  Value fstruct(std::initializer_list<double> xs) {
    std::vector<Value> v;
    for (auto x : xs) v.push_back(Value::fromFloat(x));
    return tuple(floatStruct(xs.size()), v);
  }

  // Calls a built-in by name; a boxed result is kept for release at the end.
  Value call(std::string_view name, std::vector<Value> args, TypeId result) {
    return keep(result, callBuiltin(ctx, name, args, result));
  }
  // The §8 text of a value.
  std::string text(TypeId t, Value v) {
    std::string s;
    appendValue(s, types, t, v);
    return s;
  }
  // Call and print in one step.
  std::string show(std::string_view name, std::vector<Value> args, TypeId result) {
    return text(result, call(name, std::move(args), result));
  }
};

inline Value I(std::int32_t i) { return Value::fromInt(i); }
inline Value F(double d) { return Value::fromFloat(d); }
inline Value N(NodeId n) { return Value::fromNode(n); }

}  // namespace bitest
