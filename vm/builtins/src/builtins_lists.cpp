// List built-ins of §5.6: lnth, llength, lappend, lreverse, llast, lsort, lremove,
// lremoveduplicates, lcount, lexists, lexistss, ltake, and the int-list helpers intlistdiff,
// intlistsub, intlistequal, queens_violation.
#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "builtins_util.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm::builtins {

namespace {

bool contains(const TypeTable& types, TypeId elem, Value list, Value x) {
  for (; !list.isNil(); list = listTail(list))
    if (valuesEqual(types, elem, listHead(list), x)) return true;
  return false;
}

bool containsInt(Value list, std::int32_t x) {
  for (; !list.isNil(); list = listTail(list))
    if (listHead(list).asInt() == x) return true;
  return false;
}

}  // namespace

Value lnth(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  const std::int32_t i = a[1].asInt();
  Value l = a[0];
  for (std::int32_t k = 0; k < i && !l.isNil(); ++k) l = listTail(l);
  if (i < 0 || l.isNil())
    throw error("lnth", "index " + std::to_string(i) + " out of range for a list of " +
                            std::to_string(listLength(a[0])) + " elements");
  return retained(ctx.heap, result, listHead(l));
}

Value llength(BuiltinContext&, std::span<const Value> a, TypeId) {
  return Value::fromInt(std::int32_t(listLength(a[0])));
}

Value lappend(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // Copies the first list and shares the second as the tail.
  ListBuilder lb(ctx.heap, result);
  for (Value l = a[0]; !l.isNil(); l = listTail(l)) lb.push(listHead(l));
  return lb.finish(a[1]);
}

Value lreverse(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  Value out = Value::nil();
  try {
    for (Value l = a[0]; !l.isNil(); l = listTail(l)) {
      const Value next = ctx.heap.cons(result, listHead(l), out);
      ctx.heap.release(result, out);  // the new cell holds it now
      out = next;
    }
  } catch (...) {
    ctx.heap.release(result, out);
    throw;
  }
  return out;
}

Value llast(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  Value l = a[0];
  if (l.isNil()) throw error("llast", "empty list");
  while (!listTail(l).isNil()) l = listTail(l);
  return retained(ctx.heap, result, listHead(l));
}

Value lsort(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // Ascending for int and float lists; [quirk] any other element type (node lists in the
  // established VM) gives [].
  const TypeId elem = ctx.heap.types().element(result);
  if (elem != TypeTable::kInt && elem != TypeTable::kFloat) return Value::nil();
  ctx.scratch.clear();
  for (Value l = a[0]; !l.isNil(); l = listTail(l)) ctx.scratch.push_back(listHead(l));
  if (elem == TypeTable::kInt)
    std::sort(ctx.scratch.begin(), ctx.scratch.end(), [](Value x, Value y) { return x.asInt() < y.asInt(); });
  else  // NaN after every number, so that the order stays a strict weak order
    std::sort(ctx.scratch.begin(), ctx.scratch.end(), [](Value x, Value y) {
      const double a = x.asFloat(), b = y.asFloat();
      return !std::isnan(a) && (std::isnan(b) || a < b);
    });
  return ctx.heap.makeList(result, ctx.scratch);
}

Value lremove(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // All occurrences; works for every element type (the established VM: int and node lists).
  const TypeTable& types = ctx.heap.types();
  const TypeId elem = types.element(result);
  ListBuilder lb(ctx.heap, result);
  for (Value l = a[0]; !l.isNil(); l = listTail(l))
    if (!valuesEqual(types, elem, listHead(l), a[1])) lb.push(listHead(l));
  return lb.finish();
}

Value lremoveduplicates(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // Int lists: the distinct values in the iteration order of a hash set filled in list order
  // (std::unordered_set<int32_t>, as in the established VM). Other element types: the first
  // occurrence of each value, in list order.
  const TypeTable& types = ctx.heap.types();
  const TypeId elem = types.element(result);
  if (elem == TypeTable::kInt) {
    std::unordered_set<std::int32_t> seen;
    for (Value l = a[0]; !l.isNil(); l = listTail(l)) seen.insert(listHead(l).asInt());
    ListBuilder lb(ctx.heap, result);
    for (std::int32_t x : seen) lb.push(Value::fromInt(x));
    return lb.finish();
  }
  ListBuilder lb(ctx.heap, result);
  ctx.scratch.clear();
  for (Value l = a[0]; !l.isNil(); l = listTail(l)) {
    const Value x = listHead(l);
    if (std::none_of(ctx.scratch.begin(), ctx.scratch.end(),
                     [&](Value y) { return valuesEqual(types, elem, x, y); })) {
      ctx.scratch.push_back(x);
      lb.push(x);
    }
  }
  return lb.finish();
}

Value lcount(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  if (a[0].isNil()) return Value::fromInt(0);
  const TypeTable& types = ctx.heap.types();
  const TypeId elem = types.element(objectType(a[0]));
  std::int32_t n = 0;
  for (Value l = a[0]; !l.isNil(); l = listTail(l))
    if (valuesEqual(types, elem, listHead(l), a[1])) ++n;
  return Value::fromInt(n);
}

Value lexists(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  if (a[0].isNil()) return Value::fromBool(false);
  const TypeTable& types = ctx.heap.types();
  return Value::fromBool(contains(types, types.element(objectType(a[0])), a[0], a[1]));
}

Value lexistss(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  // Some element of the second list occurs in the first (`L1 ins L2` = lexistss(L2, L1)).
  if (a[0].isNil()) return Value::fromBool(false);
  const TypeTable& types = ctx.heap.types();
  const TypeId elem = types.element(objectType(a[0]));
  for (Value l = a[1]; !l.isNil(); l = listTail(l))
    if (contains(types, elem, a[0], listHead(l))) return Value::fromBool(true);
  return Value::fromBool(false);
}

Value ltake(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // [quirk] the established VM's loop never decrements its counter: [] for n > 0, the list
  // itself for n <= 0.
  if (a[1].asInt() > 0) return Value::nil();
  return retained(ctx.heap, result, a[0]);
}

Value intlistdiff(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  ListBuilder lb(ctx.heap, result);
  for (Value l = a[0]; !l.isNil(); l = listTail(l))
    if (!containsInt(a[1], listHead(l).asInt())) lb.push(listHead(l));
  return lb.finish();
}

Value intlistsub(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // Positions [from, to), clipped to the list; empty when to <= from.
  const std::int32_t from = a[1].asInt(), to = a[2].asInt();
  ListBuilder lb(ctx.heap, result);
  std::int32_t i = 0;
  for (Value l = a[0]; !l.isNil() && i < to; l = listTail(l), ++i)
    if (i >= from) lb.push(listHead(l));
  return lb.finish();
}

Value intlistequal(BuiltinContext&, std::span<const Value> a, TypeId) {
  Value x = a[0], y = a[1];
  for (; !x.isNil() && !y.isNil(); x = listTail(x), y = listTail(y))
    if (listHead(x).asInt() != listHead(y).asInt()) return Value::fromInt(0);
  return Value::fromInt(x.isNil() && y.isNil() ? 1 : 0);
}

Value queens_violation(BuiltinContext&, std::span<const Value> a, TypeId) {
  // `cols` holds the rows of the queens already placed, most recent column first; a queen in row
  // y of the next column conflicts with the one at distance d if it is in the same row or on a
  // diagonal (row ± d).
  const std::int32_t y = a[0].asInt();
  std::int32_t d = 1;
  for (Value l = a[1]; !l.isNil(); l = listTail(l), ++d) {
    const std::int32_t r = listHead(l).asInt();
    if (r == y || r == intAdd(y, d) || r == intSub(y, d)) return Value::fromBool(true);
  }
  return Value::fromBool(false);
}

}  // namespace meldvm::builtins
