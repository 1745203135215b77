// Built-in calls allocate nothing but their results in the steady state: after a warm-up (the
// context's working buffers and the heap's free lists reach their sizes), calling the list, number,
// string, array and set built-ins performs no global operator new. Results come from the Heap's
// slab pools, which are recycled. (lremoveduplicates on int lists and filecountwords are the two
// documented exceptions and are not called here.)
#define BOOST_TEST_MODULE vm_builtins_no_allocation
#include <array>
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "../common/counting_new.hpp"
#include "meldvm/builtins.hpp"

using namespace meldvm;

namespace {

struct Workload {
  TypeTable types;
  Heap heap{types};
  BuiltinContext ctx{heap};
  Rng rng{42};
  TypeId li = types.list(TypeTable::kInt), lf = types.list(TypeTable::kFloat);
  TypeId ai = types.array(TypeTable::kInt), si = types.set(TypeTable::kInt);
  TypeId s2 = types.structOf(std::array<TypeId, 2>{TypeTable::kFloat, TypeTable::kFloat});
  TypeId s4 = types.structOf(
      std::array<TypeId, 4>{TypeTable::kFloat, TypeTable::kFloat, TypeTable::kFloat, TypeTable::kFloat});
  Value ints, ints2, fl, fl4, str, numstr, arr, set, st2, st4;
  std::uint64_t checksum = 0;

  Workload() {
    ctx.rng = &rng;
    std::array<Value, 6> xs{Value::fromInt(5), Value::fromInt(-2), Value::fromInt(9),
                            Value::fromInt(5), Value::fromInt(0),  Value::fromInt(3)};
    ints = heap.makeList(li, xs);
    ints2 = heap.makeList(li, std::span(xs).first(3));
    std::array<Value, 4> fs{Value::fromFloat(0.5), Value::fromFloat(-1), Value::fromFloat(2),
                            Value::fromFloat(0.25)};
    fl4 = heap.makeList(lf, fs);
    fl = heap.makeList(lf, std::span(fs).first(2));
    str = heap.makeString("abc");
    numstr = heap.makeString("12,-3,44");
    arr = heap.makeTuple(ai, xs);
    set = heap.makeTuple(si, xs);
    st2 = heap.makeTuple(s2, std::span(fs).first(2));
    st4 = heap.makeTuple(s4, fs);
  }
  ~Workload() {
    for (auto [t, v] : {std::pair{li, ints},
                        {li, ints2},
                        {lf, fl},
                        {lf, fl4},
                        {TypeTable::kString, str},
                        {TypeTable::kString, numstr},
                        {ai, arr},
                        {si, set},
                        {s2, st2},
                        {s4, st4}})
      heap.release(t, v);
  }

  template <std::size_t K>
  void call(std::string_view name, std::array<Value, K> args, TypeId result) {
    const BuiltinInfo* b = findBuiltin(name);
    const Value r = builtinFunction(b->id)(ctx, args, result);
    checksum += r.bits() & 0xff;
    heap.release(result, r);
  }

  void round(int r) {
    using A1 = std::array<Value, 1>;
    using A2 = std::array<Value, 2>;
    using A3 = std::array<Value, 3>;
    const Value n = Value::fromInt(r % 4), x = Value::fromInt(5);
    call("lnth", A2{ints, n}, TypeTable::kInt);
    call("llength", A1{ints}, TypeTable::kInt);
    call("lappend", A2{ints, ints2}, li);
    call("lreverse", A1{ints}, li);
    call("llast", A1{ints}, TypeTable::kInt);
    call("lsort", A1{ints}, li);
    call("lsort", A1{fl4}, lf);
    call("lremove", A2{ints, x}, li);
    call("lcount", A2{ints, x}, TypeTable::kInt);
    call("lexists", A2{ints, x}, TypeTable::kBool);
    call("lexistss", A2{ints, ints2}, TypeTable::kBool);
    call("ltake", A2{ints, n}, li);
    call("intlistdiff", A2{ints, ints2}, li);
    call("intlistsub", A3{ints, Value::fromInt(1), Value::fromInt(4)}, li);
    call("intlistequal", A2{ints, ints2}, TypeTable::kInt);
    call("queens_violation", A2{n, ints2}, TypeTable::kBool);
    call("normalize", A1{fl4}, lf);
    call("damp", A3{fl, fl4, Value::fromFloat(0.3)}, lf);
    call("divide", A2{fl, fl4}, lf);
    call("addfloatlists", A2{fl, fl4}, lf);
    call("convolve", A2{fl4, fl}, lf);
    call("residual", A2{fl, fl4}, TypeTable::kFloat);
    call("sigmoid", A1{Value::fromFloat(r)}, TypeTable::kFloat);
    call("randint", A1{Value::fromInt(100)}, TypeTable::kInt);
    call("truncate", A2{Value::fromFloat(3.14159), Value::fromInt(2)}, TypeTable::kFloat);
    call("intpower", A2{Value::fromInt(3), Value::fromInt(5)}, TypeTable::kInt);
    call("addfloatstructs", A2{st2, st2}, s2);
    call("normalizestruct", A1{st4}, s4);
    call("dampstruct", A3{st2, st2, Value::fromFloat(0.5)}, s2);
    call("residualstruct", A2{st2, st2}, TypeTable::kFloat);
    call("dividestruct", A2{st2, st2}, s2);
    call("convolvestruct", A2{st4, st2}, s2);
    call("concatenate", A2{str, numstr}, TypeTable::kString);
    call("str2int", A1{str}, TypeTable::kInt);
    call("str2float", A1{numstr}, TypeTable::kFloat);
    call("int2str", A1{Value::fromInt(-r)}, TypeTable::kString);
    call("float2str", A1{Value::fromFloat(r * 0.5)}, TypeTable::kString);
    call("str2intlist", A1{numstr}, li);
    call("array_init", A2{Value::fromInt(4), x}, ai);
    call("array_get", A2{arr, n}, TypeTable::kInt);
    call("array_set", A3{arr, n, x}, ai);
    call("array_add", A2{arr, x}, ai);
    call("array_from_list", A1{ints}, ai);
    call("array_size", A1{arr}, TypeTable::kInt);
    call("array_exists", A2{arr, x}, TypeTable::kBool);
    call("set_size", A1{set}, TypeTable::kInt);
    call("set_exists", A2{set, x}, TypeTable::kBool);
    call("set_add", A2{set, Value::fromInt(r)}, si);
    call("set_from_list", A1{ints}, si);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(steady_state_builtin_calls_allocate_nothing) {
  Workload w;
  for (int r = 0; r < 5; ++r) w.round(r);
  const std::size_t live = w.heap.liveObjects();
  const std::uint64_t before = testcommon::allocations();
  for (int r = 0; r < 100; ++r) w.round(r);
  const std::uint64_t during = testcommon::allocations() - before;
  BOOST_TEST_MESSAGE("allocations during 100 rounds: " << during << ", checksum " << w.checksum);
  BOOST_TEST(during == 0u);
  BOOST_TEST(w.checksum > 0u);
  BOOST_TEST(w.heap.liveObjects() == live);  // every result was released
}

// The counter sees the one documented exception.
BOOST_AUTO_TEST_CASE(the_counter_sees_allocations) {
  Workload w;
  const std::uint64_t before = testcommon::allocations();
  w.call("lremoveduplicates", std::array<Value, 1>{w.ints}, w.li);
  BOOST_TEST(testcommon::allocations() > before);
}
