// The built-in external functions of spec §5.6, as one table indexed by the compiler's ids.
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
};

using BuiltinFn = Value (*)(BuiltinContext& ctx, std::span<const Value> args, TypeId result);

// Argument / result type patterns. `T` is the one type variable of a polymorphic entry; `Struct`
// is any struct (of floats, for the *struct functions), and a `Struct` result has the type of the
// first argument (`Struct2`: of the second argument, for convolvestruct).
enum class Sig : std::uint8_t {
  Int,
  Float,
  Bool,
  Node,
  Thread,
  String,
  ListInt,
  ListFloat,
  ListT,
  T,
  ArrayInt,
  ArrayT,
  SetT,
  Struct,
  Struct2
};

struct BuiltinInfo {
  std::uint16_t id;       // position in the compiler's table (bytecode CALL operand)
  std::string_view name;  // as written in source, e.g. "lnth", "cpu-id"
  std::uint8_t arity;
  std::array<Sig, 4> args;
  Sig result;
  bool typeArg;  // "+type": the compiler passes the element type as a hidden argument
  BuiltinFn fn;
};

inline constexpr std::uint16_t kBuiltinIdCount = 71;  // first user extern id

// Every implemented built-in, in id order. Ids the spec lists but that are not implemented (see
// vm/README.md) are absent.
std::span<const BuiltinInfo> builtinTable();
const BuiltinInfo* findBuiltin(std::string_view name);
const BuiltinInfo* findBuiltin(std::uint16_t id);

// The concrete result type of a call with these argument types, or nullopt if they do not match
// the entry's signature (wrong count, wrong type, inconsistent T). `hint` supplies T when no
// argument fixes it (e.g. the expected type of `array_from_list([])` at the call site).
std::optional<TypeId> resolveResult(TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes,
                                    std::optional<TypeId> hint = std::nullopt);

// Whether a call with these argument types can have the concrete result type `result` (the
// verifier's check of a CALL: the interpreter trusts the types of its registers).
bool callTypesMatch(const TypeTable& types, const BuiltinInfo& b, std::span<const TypeId> argTypes, TypeId result);

// Convenience for tests and the interpreter: look up by name and call.
Value callBuiltin(BuiltinContext& ctx, std::string_view name, std::span<const Value> args, TypeId result);

namespace builtins {
// The families, each in its own source file; builtins.cpp assembles the table.
// Numeric (builtins_numeric.cpp)
Value sigmoid(BuiltinContext&, std::span<const Value>, TypeId);
Value randint(BuiltinContext&, std::span<const Value>, TypeId);
Value normalize(BuiltinContext&, std::span<const Value>, TypeId);
Value damp(BuiltinContext&, std::span<const Value>, TypeId);
Value divide(BuiltinContext&, std::span<const Value>, TypeId);
Value convolve(BuiltinContext&, std::span<const Value>, TypeId);
Value addfloatlists(BuiltinContext&, std::span<const Value>, TypeId);
Value truncate(BuiltinContext&, std::span<const Value>, TypeId);
Value float2int(BuiltinContext&, std::span<const Value>, TypeId);
Value residual(BuiltinContext&, std::span<const Value>, TypeId);
Value intpower(BuiltinContext&, std::span<const Value>, TypeId);
Value addfloatstructs(BuiltinContext&, std::span<const Value>, TypeId);
Value normalizestruct(BuiltinContext&, std::span<const Value>, TypeId);
Value dampstruct(BuiltinContext&, std::span<const Value>, TypeId);
Value residualstruct(BuiltinContext&, std::span<const Value>, TypeId);
Value dividestruct(BuiltinContext&, std::span<const Value>, TypeId);
Value convolvestruct(BuiltinContext&, std::span<const Value>, TypeId);
Value fabs(BuiltinContext&, std::span<const Value>, TypeId);
// Lists (builtins_lists.cpp)
Value intlistdiff(BuiltinContext&, std::span<const Value>, TypeId);
Value lnth(BuiltinContext&, std::span<const Value>, TypeId);
Value lremove(BuiltinContext&, std::span<const Value>, TypeId);
Value intlistsub(BuiltinContext&, std::span<const Value>, TypeId);
Value llength(BuiltinContext&, std::span<const Value>, TypeId);
Value lappend(BuiltinContext&, std::span<const Value>, TypeId);
Value lreverse(BuiltinContext&, std::span<const Value>, TypeId);
Value llast(BuiltinContext&, std::span<const Value>, TypeId);
Value lsort(BuiltinContext&, std::span<const Value>, TypeId);
Value lremoveduplicates(BuiltinContext&, std::span<const Value>, TypeId);
Value intlistequal(BuiltinContext&, std::span<const Value>, TypeId);
Value lcount(BuiltinContext&, std::span<const Value>, TypeId);
Value lexists(BuiltinContext&, std::span<const Value>, TypeId);
Value lexistss(BuiltinContext&, std::span<const Value>, TypeId);
Value queens_violation(BuiltinContext&, std::span<const Value>, TypeId);
Value ltake(BuiltinContext&, std::span<const Value>, TypeId);
// Strings (builtins_strings.cpp)
Value concatenate(BuiltinContext&, std::span<const Value>, TypeId);
Value str2float(BuiltinContext&, std::span<const Value>, TypeId);
Value str2int(BuiltinContext&, std::span<const Value>, TypeId);
Value int2str(BuiltinContext&, std::span<const Value>, TypeId);
Value float2str(BuiltinContext&, std::span<const Value>, TypeId);
Value str2intlist(BuiltinContext&, std::span<const Value>, TypeId);
Value filecountwords(BuiltinContext&, std::span<const Value>, TypeId);
// Arrays, sets, nodes, threads, time (builtins_misc.cpp)
Value wastetime(BuiltinContext&, std::span<const Value>, TypeId);
Value priority(BuiltinContext&, std::span<const Value>, TypeId);
Value cpu_id(BuiltinContext&, std::span<const Value>, TypeId);
Value node2int(BuiltinContext&, std::span<const Value>, TypeId);
Value cpu_static(BuiltinContext&, std::span<const Value>, TypeId);
Value is_moving(BuiltinContext&, std::span<const Value>, TypeId);
Value is_static(BuiltinContext&, std::span<const Value>, TypeId);
Value queue_size(BuiltinContext&, std::span<const Value>, TypeId);
Value facts_proved(BuiltinContext&, std::span<const Value>, TypeId);
Value facts_consumed(BuiltinContext&, std::span<const Value>, TypeId);
Value array_init(BuiltinContext&, std::span<const Value>, TypeId);
Value array_get(BuiltinContext&, std::span<const Value>, TypeId);
Value array_set(BuiltinContext&, std::span<const Value>, TypeId);
Value array_add(BuiltinContext&, std::span<const Value>, TypeId);
Value array_from_list(BuiltinContext&, std::span<const Value>, TypeId);
Value array_size(BuiltinContext&, std::span<const Value>, TypeId);
Value array_exists(BuiltinContext&, std::span<const Value>, TypeId);
// Benchmark and placement helpers (builtins_helpers.cpp)
Value minimax_score(BuiltinContext&, std::span<const Value>, TypeId);
Value minimax_points(BuiltinContext&, std::span<const Value>, TypeId);
Value minimax_score2(BuiltinContext&, std::span<const Value>, TypeId);
Value minimax_points2(BuiltinContext&, std::span<const Value>, TypeId);
Value degeneratevector(BuiltinContext&, std::span<const Value>, TypeId);
Value demergemessages(BuiltinContext&, std::span<const Value>, TypeId);
Value partition_vertical(BuiltinContext&, std::span<const Value>, TypeId);
Value partition_horizontal(BuiltinContext&, std::span<const Value>, TypeId);
Value partition_grid(BuiltinContext&, std::span<const Value>, TypeId);
}  // namespace builtins

}  // namespace meldvm
