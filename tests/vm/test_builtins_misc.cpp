#define BOOST_TEST_MODULE vm_builtins_misc
#include <boost/test/unit_test.hpp>
#include <chrono>
#include <set>

#include "builtins_fixture.hpp"

using namespace bitest;

namespace {

struct FakeScheduler : SchedulerView {
  double priority(NodeId n) const override { return n * 1.5; }
  ThreadId owner(NodeId n) const override { return n % 2; }
  std::int32_t staticNodes(ThreadId t) const override { return t == 0 ? 3 : 7; }
  bool isStatic(NodeId n) const override { return n == 4; }
  std::int32_t queueSize(NodeId n) const override { return std::int32_t(n) + 10; }
  std::int32_t factsProved() const override { return 12; }
  std::int32_t factsConsumed() const override { return 5; }
  std::int32_t threadCount() const override { return 4; }
};

}  // namespace

BOOST_FIXTURE_TEST_SUITE(misc, Fix)

BOOST_AUTO_TEST_CASE(wastetime_sleeps_and_returns_its_argument) {
  BOOST_CHECK_EQUAL(call("wastetime", {I(0)}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("wastetime", {I(-3)}, tInt).asInt(), -3);
  const auto t0 = std::chrono::steady_clock::now();
  BOOST_CHECK_EQUAL(call("wastetime", {I(20)}, tInt).asInt(), 20);
  BOOST_CHECK(std::chrono::steady_clock::now() - t0 >= std::chrono::milliseconds(20));
}

BOOST_AUTO_TEST_CASE(node2int_is_the_internal_id) {
  BOOST_CHECK_EQUAL(call("node2int", {N(5)}, tInt).asInt(), 5);
  BOOST_CHECK_EQUAL(call("node2int", {N(0)}, tInt).asInt(), 0);
}

BOOST_AUTO_TEST_CASE(scheduler_queries) {
  FakeScheduler s;
  ctx.sched = &s;
  BOOST_CHECK_EQUAL(show("priority", {N(3)}, tFloat), "4.5");
  BOOST_CHECK_EQUAL(show("cpu-id", {N(3)}, tThread), "#T1");
  BOOST_CHECK_EQUAL(show("cpu-id", {N(2)}, tThread), "#T0");
  BOOST_CHECK_EQUAL(call("cpu-static", {N(2)}, tInt).asInt(), 3);
  BOOST_CHECK_EQUAL(call("cpu-static", {N(1)}, tInt).asInt(), 7);
  BOOST_CHECK(call("is-static", {N(4)}, tBool).asBool());
  BOOST_CHECK(!call("is-moving", {N(4)}, tBool).asBool());
  BOOST_CHECK(!call("is-static", {N(1)}, tBool).asBool());
  BOOST_CHECK(call("is-moving", {N(1)}, tBool).asBool());
  BOOST_CHECK_EQUAL(call("queue-size", {N(2)}, tInt).asInt(), 12);
  BOOST_CHECK_EQUAL(call("facts-proved", {N(0)}, tInt).asInt(), 12);
  BOOST_CHECK_EQUAL(call("facts-consumed", {N(0)}, tInt).asInt(), 5);
  ctx.sched = nullptr;
  for (const char* f : {"priority", "cpu-id", "cpu-static", "is-moving", "is-static", "queue-size",
                        "facts-proved", "facts-consumed"})
    BOOST_CHECK_THROW(call(f, {N(0)}, tInt), RuntimeError);
}

BOOST_AUTO_TEST_CASE(arrays) {
  BOOST_CHECK_EQUAL(show("array_init", {I(3), I(0)}, tAI), "#[0, 0, 0]");
  BOOST_CHECK_EQUAL(show("array_init", {I(0), I(7)}, tAI), "#[]");
  BOOST_CHECK_THROW(call("array_init", {I(-1), I(7)}, tAI), RuntimeError);
  BOOST_CHECK_EQUAL(show("array_init", {I(2), str("s")}, tAS), "#[\"s\", \"s\"]");
  const Value a = tuple(tAI, {I(4), I(5), I(6)});
  BOOST_CHECK_EQUAL(call("array_get", {a, I(1)}, tInt).asInt(), 5);
  BOOST_CHECK_THROW(call("array_get", {a, I(3)}, tInt), RuntimeError);
  BOOST_CHECK_THROW(call("array_get", {a, I(-1)}, tInt), RuntimeError);
  BOOST_CHECK_EQUAL(show("array_set", {a, I(0), I(9)}, tAI), "#[9, 5, 6]");
  BOOST_CHECK_EQUAL(text(tAI, a), "#[4, 5, 6]");  // functional update
  BOOST_CHECK_THROW(call("array_set", {a, I(3), I(9)}, tAI), RuntimeError);
  BOOST_CHECK_EQUAL(show("array_add", {a, I(7)}, tAI), "#[4, 5, 6, 7]");
  BOOST_CHECK_EQUAL(show("array_add", {tuple(tAI, {}), I(2)}, tAI), "#[2]");
  BOOST_CHECK_EQUAL(show("array_from_list", {ints({1, 2})}, tAI), "#[1, 2]");
  BOOST_CHECK_EQUAL(show("array_from_list", {Value::nil()}, tAI), "#[]");
  BOOST_CHECK_EQUAL(call("array_size", {a}, tInt).asInt(), 3);
  BOOST_CHECK_EQUAL(call("array_size", {tuple(tAI, {})}, tInt).asInt(), 0);
  BOOST_CHECK(call("array_exists", {a, I(6)}, tBool).asBool());
  BOOST_CHECK(!call("array_exists", {a, I(8)}, tBool).asBool());
  const Value as = tuple(tAS, {str("x"), str("y")});
  BOOST_CHECK_EQUAL(show("array_get", {as, I(1)}, tString), "\"y\"");
  BOOST_CHECK(call("array_exists", {as, str("x")}, tBool).asBool());
}

BOOST_AUTO_TEST_CASE(sets) {
  const Value s = call("set_from_list", {ints({3, 1, 3})}, tSI);
  BOOST_CHECK_EQUAL(text(tSI, s), "{3, 1}");
  BOOST_CHECK_EQUAL(call("set_size", {s}, tInt).asInt(), 2);
  BOOST_CHECK(call("set_exists", {s, I(1)}, tBool).asBool());
  BOOST_CHECK(!call("set_exists", {s, I(2)}, tBool).asBool());
  BOOST_CHECK_EQUAL(show("set_add", {s, I(2)}, tSI), "{3, 1, 2}");
  BOOST_CHECK_EQUAL(show("set_add", {s, I(1)}, tSI), "{3, 1}");
  BOOST_CHECK_EQUAL(text(tSI, s), "{3, 1}");
  const Value e = call("set_from_list", {Value::nil()}, tSI);
  BOOST_CHECK_EQUAL(text(tSI, e), "{}");
  BOOST_CHECK_EQUAL(call("set_size", {e}, tInt).asInt(), 0);
}

BOOST_AUTO_TEST_CASE(the_table_follows_the_compiler_ids) {
  const std::pair<int, const char*> expected[] = {{0, "sigmoid"},
                                                  {1, "randint"},
                                                  {2, "normalize"},
                                                  {3, "damp"},
                                                  {4, "divide"},
                                                  {5, "convolve"},
                                                  {6, "addfloatlists"},
                                                  {7, "intlistdiff"},
                                                  {8, "lnth"},
                                                  {9, "concatenate"},
                                                  {10, "str2float"},
                                                  {11, "str2int"},
                                                  {12, "lremove"},
                                                  {13, "wastetime"},
                                                  {14, "truncate"},
                                                  {15, "float2int"},
                                                  {16, "int2str"},
                                                  {17, "float2str"},
                                                  {18, "intlistsub"},
                                                  {19, "str2intlist"},
                                                  {20, "filecountwords"},
                                                  {21, "residual"},
                                                  {22, "llength"},
                                                  {23, "lappend"},
                                                  {24, "priority"},
                                                  {25, "lreverse"},
                                                  {26, "llast"},
                                                  {27, "cpu-id"},
                                                  {28, "node2int"},
                                                  {29, "intpower"},
                                                  {30, "lsort"},
                                                  {31, "lremoveduplicates"},
                                                  {32, "degeneratevector"},
                                                  {33, "demergemessages"},
                                                  {34, "intlistequal"},
                                                  {35, "addfloatstructs"},
                                                  {36, "normalizestruct"},
                                                  {37, "dampstruct"},
                                                  {38, "residualstruct"},
                                                  {39, "dividestruct"},
                                                  {40, "convolvestruct"},
                                                  {41, "cpu-static"},
                                                  {42, "is-moving"},
                                                  {43, "is-static"},
                                                  {44, "partition_vertical"},
                                                  {45, "partition_horizontal"},
                                                  {46, "partition_grid"},
                                                  {47, "queue-size"},
                                                  {48, "facts-proved"},
                                                  {49, "facts-consumed"},
                                                  {50, "lcount"},
                                                  {51, "lexists"},
                                                  {52, "lexistss"},
                                                  {53, "queens_violation"},
                                                  {54, "minimax_score"},
                                                  {55, "minimax_points"},
                                                  {56, "array_init"},
                                                  {57, "array_get"},
                                                  {58, "array_set"},
                                                  {59, "array_add"},
                                                  {60, "array_from_list"},
                                                  {61, "array_size"},
                                                  {62, "minimax_score2"},
                                                  {63, "minimax_points2"},
                                                  {64, "fabs"},
                                                  {65, "set_size"},
                                                  {66, "set_exists"},
                                                  {67, "set_add"},
                                                  {68, "set_from_list"},
                                                  {69, "array_exists"},
                                                  {70, "ltake"}};
  const auto table = builtinTable();
  BOOST_REQUIRE_EQUAL(table.size(), std::size(expected));
  for (std::size_t i = 0; i < table.size(); ++i) {
    BOOST_CHECK_EQUAL(table[i].id, expected[i].first);
    BOOST_CHECK_EQUAL(table[i].name, expected[i].second);
    BOOST_CHECK(builtinFunction(table[i].id) != nullptr);
    BOOST_CHECK_EQUAL(findBuiltin(table[i].name), &table[i]);
    BOOST_CHECK_EQUAL(findBuiltin(table[i].id), &table[i]);
  }
  // Every id of §5.6 is in the table (ids 0..70, in order); the next one is the first user extern.
  for (std::size_t i = 0; i < table.size(); ++i) BOOST_CHECK_EQUAL(table[i].id, i);
  BOOST_CHECK(!findBuiltin(std::uint16_t(71)));
  BOOST_CHECK(!findBuiltin("nosuch"));
  // The entries marked "+type" in §5.6 (the compiler passes the element type).
  const std::set<int> typed = {12, 23, 25, 30, 31, 35, 36, 37, 38, 39, 40,
                               50, 51, 52, 56, 58, 59, 60, 66, 67, 68, 69};
  for (const BuiltinInfo& b : table) BOOST_CHECK_EQUAL(b.typeArg, typed.count(b.id) == 1);
  BOOST_CHECK_THROW(call("nosuch", {}, tInt), RuntimeError);
  BOOST_CHECK_THROW(call("lnth", {Value::nil()}, tInt), RuntimeError);  // wrong arity
}

BOOST_AUTO_TEST_CASE(result_types_resolve_polymorphic_signatures) {
  auto res = [&](const char* name, std::vector<TypeId> args, std::optional<TypeId> hint = {}) {
    return resolveResult(types, *findBuiltin(name), args, hint);
  };
  BOOST_CHECK(res("lnth", {tLI, tInt}) == tInt);
  BOOST_CHECK(res("lnth", {tLS, tInt}) == tString);
  BOOST_CHECK(res("lnth", {tLLI, tInt}) == tLI);
  BOOST_CHECK(res("lappend", {tLN, tLN}) == tLN);
  BOOST_CHECK(!res("lappend", {tLI, tLF}));
  BOOST_CHECK(!res("lnth", {tLI, tFloat}));
  BOOST_CHECK(!res("lnth", {tLI}));
  BOOST_CHECK(res("lremove", {tLN, tNode}) == tLN);
  BOOST_CHECK(!res("lremove", {tLN, tInt}));
  BOOST_CHECK(res("array_from_list", {tLF}) == types.array(tFloat));
  BOOST_CHECK(res("array_init", {tInt, tString}) == tAS);
  BOOST_CHECK(res("set_add", {tSI, tInt}) == tSI);
  BOOST_CHECK(res("sigmoid", {tFloat}) == tFloat);
  BOOST_CHECK(!res("sigmoid", {tInt}));
  BOOST_CHECK(res("normalize", {tLF}) == tLF);
  BOOST_CHECK(!res("normalize", {tLI}));
  BOOST_CHECK(res("cpu-id", {tNode}) == tThread);
  const TypeId s2 = floatStruct(2), s4 = floatStruct(4);
  BOOST_CHECK(res("addfloatstructs", {s2, s2}) == s2);
  BOOST_CHECK(res("convolvestruct", {s4, s2}) == s2);
  BOOST_CHECK(res("residualstruct", {s2, s2}) == tFloat);
  BOOST_CHECK(!res("addfloatstructs", {types.structOf(std::vector<TypeId>{tInt}), s2}));
  BOOST_CHECK(res("intlistdiff", {tLI, tLI}) == tLI);
  BOOST_CHECK(res("str2intlist", {tString}) == tLI);
}

BOOST_AUTO_TEST_SUITE_END()
