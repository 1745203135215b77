// The implementations of the built-in external functions of spec §5.6 (builtins.def lists them).
//
// Calling convention: `fn(ctx, args, result)`. `args` are borrowed (the caller keeps its
// references); `result` is the concrete result type of this call site (for polymorphic entries
// the interpreter resolves it once with resolveResult()). A boxed result is a new reference that
// the caller owns and must release; returning an argument or one of its elements counts as a new
// reference too (it is retained). New strings, lists, structs, arrays and sets come from the
// context's Heap; working storage comes from the context's reusable buffers, so a call allocates
// nothing else once the buffers have grown (exceptions: lremoveduplicates builds a hash set,
// filecountwords opens a file).
//
// Errors the spec defines ("aborts": lnth/llast/array index out of range, empty list) and inputs
// that have no meaning (randint(0), a missing scheduler view) raise RuntimeError (arith.hpp).
//
// Functions the established VM implements as instructions (priority, cpu-id, cpu-static,
// is-moving, is-static, facts-proved, facts-consumed, fabs) and queue-size read the scheduler
// through the SchedulerView interface of the context.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meldvm/arith.hpp"
#include "meldvm/builtin_signatures.hpp"
#include "meldvm/heap.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value.hpp"
#include "support/splitmix.hpp"

namespace meldvm {

// What the scheduler tells the node-placement functions. The VM's scheduler implements it; tests
// use a fake.
class SchedulerView {
 public:
  virtual ~SchedulerView() = default;
  virtual double priority(NodeId n) const = 0;             // current priority of n
  virtual ThreadId owner(NodeId n) const = 0;              // thread that owns n
  virtual std::int32_t staticNodes(ThreadId t) const = 0;  // static nodes owned by t
  virtual bool isStatic(NodeId n) const = 0;
  virtual std::int32_t queueSize(NodeId n) const = 0;  // work queue size of n's owner thread
  virtual std::int32_t factsProved() const = 0;        // in the current run of the host node
  virtual std::int32_t factsConsumed() const = 0;
  virtual std::int32_t threadCount() const = 0;  // VM threads (the partition_* functions)
};

// The random stream of one VM thread (the project's SplitMix64), seeded per thread, so that serial
// runs are reproducible (§5.6 randint).
struct Rng : support::SplitMix64 {
  static Rng forThread(ThreadId t) { return Rng{{0x6d656c64ull * support::kGolden + t}}; }
};

struct BuiltinContext {
  explicit BuiltinContext(Heap& h) : heap(h) {}
  Heap& heap;
  Rng* rng = nullptr;                    // the running thread's stream (randint)
  const SchedulerView* sched = nullptr;  // node placement / priority functions
  // Reused working storage (not part of the interface).
  std::vector<Value> scratch;
  std::vector<double> numbers;
  std::string text;
  // convolve's last matrix and the exponentials of its entries: belief propagation convolves with
  // one constant matrix throughout, so each call takes n exponentials instead of n * n.
  std::vector<double> convolveMatrix, convolveMatrixExp;
};

using BuiltinFn = Value (*)(BuiltinContext& ctx, std::span<const Value> args, TypeId result);

// Convenience for tests and the interpreter: look up by name and call.
Value callBuiltin(BuiltinContext& ctx, std::string_view name, std::span<const Value> args, TypeId result);

// The implementations, one per line of builtins.def (the set functions share the array ones); they
// live by family in builtins_numeric, _lists, _strings, _misc (arrays, sets, nodes, threads, time)
// and _helpers (benchmark and placement helpers).
namespace builtins {
#define BUILTIN(ID, NAME, IMPL, SIG, TYPE_ARG) Value IMPL(BuiltinContext&, std::span<const Value>, TypeId);
#include "meldvm/builtins.def"
#undef BUILTIN
}  // namespace builtins

inline constexpr BuiltinFn kBuiltinFunctions[] = {
#define BUILTIN(ID, NAME, IMPL, SIG, TYPE_ARG) builtins::IMPL,
#include "meldvm/builtins.def"
#undef BUILTIN
};
static_assert(std::size(kBuiltinFunctions) == kBuiltinIdCount);

// The implementation of the built-in with this id (builtins.def), or nullptr when there is none.
inline BuiltinFn builtinFunction(std::uint16_t id) {
  return id < kBuiltinIdCount ? kBuiltinFunctions[id] : nullptr;
}

}  // namespace meldvm
