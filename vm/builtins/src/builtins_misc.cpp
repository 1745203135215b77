// Built-ins of §5.6 on arrays, sets, nodes, threads and time: array_*, set_*, node2int,
// wastetime, and the scheduler queries (priority, cpu-id, cpu-static, is-moving, is-static,
// queue-size, facts-proved, facts-consumed) answered by the context's SchedulerView.
#include <chrono>
#include <thread>

#include "builtins_util.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm::builtins {

namespace {

const SchedulerView& sched(BuiltinContext& ctx, std::string_view fn) {
  if (!ctx.sched) throw error(fn, "no scheduler in the context");
  return *ctx.sched;
}

std::size_t index(std::string_view fn, std::int32_t i, std::size_t size) {
  if (i < 0 || std::size_t(i) >= size)
    throw error(fn, "index " + std::to_string(i) + " out of range for an array of " + std::to_string(size) +
                        " elements");
  return std::size_t(i);
}

bool tupleContains(const TypeTable& types, Value tuple, Value x) {
  const TypeId elem = types.element(objectType(tuple));
  for (Value v : tupleItems(tuple))
    if (valuesEqual(types, elem, v, x)) return true;
  return false;
}

}  // namespace

Value wastetime(BuiltinContext&, std::span<const Value> a, TypeId) {
  if (a[0].asInt() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(a[0].asInt()));
  return a[0];
}

Value node2int(BuiltinContext&, std::span<const Value> a, TypeId) {
  // Node values already hold the internal (renumbered, §6.1) id.
  return Value::fromInt(std::int32_t(a[0].asNode()));
}

Value priority(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return Value::fromFloat(sched(ctx, "priority").priority(a[0].asNode()));
}
Value cpu_id(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return Value::fromThread(sched(ctx, "cpu-id").owner(a[0].asNode()));
}
Value cpu_static(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  const SchedulerView& s = sched(ctx, "cpu-static");
  return Value::fromInt(s.staticNodes(s.owner(a[0].asNode())));
}
Value is_moving(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return Value::fromBool(!sched(ctx, "is-moving").isStatic(a[0].asNode()));
}
Value is_static(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return Value::fromBool(sched(ctx, "is-static").isStatic(a[0].asNode()));
}
Value queue_size(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return Value::fromInt(sched(ctx, "queue-size").queueSize(a[0].asNode()));
}
Value facts_proved(BuiltinContext& ctx, std::span<const Value>, TypeId) {
  return Value::fromInt(sched(ctx, "facts-proved").factsProved());
}
Value facts_consumed(BuiltinContext& ctx, std::span<const Value>, TypeId) {
  return Value::fromInt(sched(ctx, "facts-consumed").factsConsumed());
}

Value array_init(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  const std::int32_t n = a[0].asInt();
  if (n < 0) throw error("array_init", "negative size " + std::to_string(n));
  // Arrays are values (array_set copies): past 2^20 items (8 MB a copy) a size is a runaway value.
  if (n > (1 << 20)) throw error("array_init", "size " + std::to_string(n) + " is larger than 2^20 items");
  ctx.scratch.assign(std::size_t(n), a[1]);
  return ctx.heap.makeTuple(result, ctx.scratch);
}

Value array_get(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  const auto items = tupleItems(a[0]);
  return retained(ctx.heap, result, items[index("array_get", a[1].asInt(), items.size())]);
}

Value array_set(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  const auto items = tupleItems(a[0]);
  const std::size_t i = index("array_set", a[1].asInt(), items.size());
  ctx.scratch.assign(items.begin(), items.end());
  ctx.scratch[i] = a[2];
  return ctx.heap.makeTuple(result, ctx.scratch);
}

Value array_add(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  const auto items = tupleItems(a[0]);
  ctx.scratch.assign(items.begin(), items.end());
  ctx.scratch.push_back(a[1]);
  return ctx.heap.makeTuple(result, ctx.scratch);
}

Value array_from_list(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  ctx.scratch.clear();
  for (Value l = a[0]; !l.isNil(); l = listTail(l)) ctx.scratch.push_back(listHead(l));
  return ctx.heap.makeTuple(result, ctx.scratch);
}

Value array_size(BuiltinContext&, std::span<const Value> a, TypeId) {
  return Value::fromInt(std::int32_t(tupleItems(a[0]).size()));
}

Value array_exists(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return Value::fromBool(tupleContains(ctx.heap.types(), a[0], a[1]));
}

}  // namespace meldvm::builtins
