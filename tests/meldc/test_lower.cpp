// Back end: tables (types, predicates, nodes, strings, globals, functions, scheduling), rule 0
// and the axiom blocks (§6.2), expressions and heads, unsupported constructs.
#define BOOST_TEST_MODULE meldc_lower
#include <algorithm>
#include <bit>
#include <boost/test/unit_test.hpp>
#include <limits>

#include "lower_support.hpp"

using meldvm::Opcode;
using namespace meldvm;

namespace {

// The int immediates of MOVI in a block, in code order.
std::vector<std::int32_t> movi(const CodeBlock& b) {
  std::vector<std::int32_t> out;
  for (const Instr& i : only(b, Opcode::MOVI)) out.push_back(std::int32_t(i.operands.at(1)));
  return out;
}

double movf(const Instr& i) {
  return std::bit_cast<double>(std::uint64_t(i.operands.at(1)) | std::uint64_t(i.operands.at(2)) << 32);
}

}  // namespace

BOOST_AUTO_TEST_CASE(predicate_table_order_and_properties) {
  Lowered l(
      "type linear a(node, int).\ntype route e(node, node).\ntype p(node, min int, list float).\n"
      "compact e.\n!e(@1, @2).\na(A, N) -o setColor2(A, N), set-priority(A, 2.0).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const PredicateTable& t = l.p().predicates;
  BOOST_REQUIRE_EQUAL(t.size(), 5u);  // _init, setcolor2 (used built-in), a, e, p; no set-priority
  BOOST_TEST(t[0].name == "_init");
  BOOST_TEST(l.p().initPredicate == 0u);
  BOOST_TEST(t[0].linear);
  BOOST_TEST(t[1].name == "setcolor2");
  BOOST_TEST(t[1].action);
  BOOST_TEST(!t[1].linear);
  BOOST_TEST(t[2].name == "a");
  BOOST_TEST(t[2].linear);
  BOOST_TEST(t[2].fields == std::vector<TypeId>{TypeTable::kInt});
  BOOST_TEST(t[3].route);
  BOOST_TEST(t[3].compact);
  BOOST_TEST((t[4].aggregate == AggregateKind::Min));
  BOOST_TEST(t[4].aggregateField == 0u);
  BOOST_TEST((l.p().types.kind(t[4].fields.at(1)) == TypeKind::List));
  BOOST_TEST(l.p().types.element(t[4].fields.at(1)) == TypeTable::kFloat);
  BOOST_TEST(only(l.rule(1), Opcode::ACTION).size() == 1u);
  BOOST_TEST(only(l.rule(1), Opcode::SET_PRIORITY).size() == 1u);
  // nodes: @1 and @2 renumbered
  BOOST_TEST(l.p().nodeSourceIds.size() == 2u);
  BOOST_TEST(l.p().nodeAxioms.size() == 2u);
}

BOOST_AUTO_TEST_CASE(constant_axioms_in_spec_order) {
  // §6.2: evaluated axioms in reverse source order (9, then 7), then literal facts by predicate
  Lowered l(
      "type linear a(node, int).\ntype linear b(node, int).\n"
      "a(@0, 1). a(@0, lnth([7, 8], 0)). b(@0, 5). a(@0, 3). a(@0, lnth([9], 0)).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().axiomBlocks.size(), 1u);
  BOOST_TEST(l.p().nodeAxioms.at(0) == 0u);
  const CodeBlock& b = l.p().axiomBlocks[0];
  // The evaluated ones by DERIVE, the literal ones as AXIOM_FACTS data (one int field: a word each).
  std::vector<PredId> derived;
  std::vector<std::int32_t> data;
  for (const Instr& i : decode(b)) {
    if (i.op == Opcode::DERIVE) derived.push_back(i.operands.at(0));
    if (i.op != Opcode::AXIOM_FACTS) continue;
    BOOST_TEST(i.operands.at(1) == i.operands.size() - 2);
    for (std::size_t k = 2; k < i.operands.size(); ++k) {
      derived.push_back(i.operands.at(0));
      data.push_back(std::int32_t(i.operands[k]));
    }
  }
  const PredId a = l.pred("a"), bb = l.pred("b");
  BOOST_TEST(derived == (std::vector<PredId>{a, a, a, a, bb}));
  BOOST_TEST(movi(b) == (std::vector<std::int32_t>{9, 0, 8, 7, 0}));
  BOOST_TEST(data == (std::vector<std::int32_t>{1, 3, 5}));
  BOOST_TEST(opNames(b).ends_with("CALL DERIVE AXIOM_FACTS AXIOM_FACTS RET"), opNames(b));
  BOOST_TEST(only(b, Opcode::CALL).size() == 2u);
}

BOOST_AUTO_TEST_CASE(rule_zero_and_variable_axioms) {
  Lowered l("type linear a(node, int).\ntype linear b(node).\na(X, 2).\nb(@0).\n!setColor2(X, 4).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const meldvm::Rule& r0 = l.p().rules.at(0);
  BOOST_TEST(r0.bodyPredicates == std::vector<PredId>{l.p().initPredicate});
  BOOST_TEST(opNames(r0.block) == "ITER AXIOMS HOST MOVI DERIVE HOST MOVI ACTION FIRE NEXT RET");
  const auto iter = only(r0.block, Opcode::ITER).at(0);
  BOOST_TEST(iter.operands.at(2) == std::uint32_t(kIterLinear | kIterConsume | kIterConsumableClass));
  BOOST_TEST(l.p().axiomBlocks.size() == 1u);
}

BOOST_AUTO_TEST_CASE(axioms_of_literal_homes_go_to_their_node) {
  Lowered l("type route e(node, node).\n!e(@5, @7).\n!e(@7, @5).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().axiomBlocks.size(), 2u);
  for (std::uint32_t n = 0; n < 2; ++n) {
    const CodeBlock& b = l.p().axiomBlocks.at(l.p().nodeAxioms.at(n));
    BOOST_TEST(opNames(b) == "AXIOM_FACTS RET");
    // One fact of one node field: predicate, count 1, the other node.
    BOOST_TEST(only(b, Opcode::AXIOM_FACTS).at(0).operands ==
               (std::vector<std::uint32_t>{l.pred("e"), 1, 1u - n}));
  }
}

BOOST_AUTO_TEST_CASE(literals_get_the_type_of_their_place) {
  Lowered l(
      "type linear f(node, float).\ntype linear g(node, float).\nf(@0, 2).\n"
      "f(A, X) -o g(A, X * 0.85 + 1).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto axioms = only(l.p().axiomBlocks.at(0), Opcode::AXIOM_FACTS);
  BOOST_REQUIRE_EQUAL(axioms.size(), 1u);
  BOOST_REQUIRE_EQUAL(axioms[0].operands.size(), 4u);  // predicate, count 2, the double's two words
  BOOST_TEST(std::bit_cast<double>(std::uint64_t(axioms[0].operands[2]) | std::uint64_t(axioms[0].operands[3])
                                                                              << 32) == 2.0);
  const auto floats = only(l.rule(1), Opcode::MOVF);
  BOOST_REQUIRE_EQUAL(floats.size(), 2u);
  BOOST_TEST(movf(floats[0]) == double(0.85f));  // single precision, §1.4
  BOOST_TEST(movf(floats[1]) == 1.0);
  BOOST_TEST(only(l.rule(1), Opcode::MULF).size() == 1u);
  BOOST_TEST(only(l.rule(1), Opcode::ADDF).size() == 1u);
}

BOOST_AUTO_TEST_CASE(constants_fold_or_become_globals) {
  Lowered l(
      "type linear a(node, int).\nconst k = 2 * 3 + 1.\nconst n = @world.\n"
      "const s = str2int(@arg2).\na(@0, 1). a(@1, 2).\na(A, X) -o a(A, X + k + n + s).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().globals.size(), 1u);
  BOOST_TEST(l.p().globals[0].name == "s");
  BOOST_TEST(l.p().globals[0].type == TypeTable::kInt);
  BOOST_TEST(l.p().highestArg == 2u);
  BOOST_TEST(opNames(l.p().globalsInit) == "ARG CALL SETGLOBAL RET");
  BOOST_TEST(only(l.rule(1), Opcode::GLOBAL).size() == 1u);
  const auto ints = movi(l.rule(1));
  BOOST_TEST(std::count(ints.begin(), ints.end(), 7) == 1);
  BOOST_TEST(std::count(ints.begin(), ints.end(), 2) == 1);  // @world: two nodes
}

BOOST_AUTO_TEST_CASE(arithmetic_on_constants_folds_in_rule_bodies_and_heads) {
  // `size - 1`, `(1.0 - d)`, `d / float(size)`: one move each, computed as the VM computes them
  // (doubles from single-precision literals, 32-bit wrap-around); a division by zero is left to the
  // run-time error, and anything with a variable is computed at run time.
  Lowered l(
      "type linear a(node, int).\ntype linear b(node, float).\nconst size = 11.\nconst d = 0.15.\n"
      "a(@0, 1). b(@0, 1.0).\n"
      "a(A, X) -o a(A, X + (size - 1) * 2 + (2147483647 + 1)).\n"
      "b(A, F) -o b(A, F * (1.0 - d) + d / float(size)).\n"
      "a(A, X), X > 5 -o a(A, X + 1 / (size - 11)).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto ints = movi(l.rule(1));
  BOOST_TEST(std::count(ints.begin(), ints.end(), 20) == 1);
  BOOST_TEST(std::count(ints.begin(), ints.end(), std::numeric_limits<std::int32_t>::min()) == 1);
  BOOST_TEST(only(l.rule(1), Opcode::ADDI).size() == 2u);  // X + 20, then + INT32_MIN
  BOOST_TEST(only(l.rule(1), Opcode::SUBI).empty());
  BOOST_TEST(only(l.rule(1), Opcode::MULI).empty());
  const double dd = double(0.15f);
  std::vector<double> floats;
  for (const Instr& i : only(l.rule(2), Opcode::MOVF)) floats.push_back(movf(i));
  BOOST_TEST(floats == (std::vector<double>{1.0 - dd, dd / 11.0}));
  BOOST_TEST(only(l.rule(2), Opcode::MULF).size() == 1u);
  BOOST_TEST(only(l.rule(2), Opcode::ADDF).size() == 1u);
  BOOST_TEST(only(l.rule(2), Opcode::SUBF).empty());
  BOOST_TEST(only(l.rule(2), Opcode::DIVF).empty());
  BOOST_TEST(only(l.rule(2), Opcode::I2F).empty());
  BOOST_TEST(only(l.rule(3), Opcode::DIVI).size() == 1u);  // 1 / 0: the VM's error at run time
}

BOOST_AUTO_TEST_CASE(functions_take_registers_and_return_in_the_next) {
  Lowered l(
      "type linear a(node, int).\nfun sq(int X) : int = X * X.\nfun abs(int X) : int = if X >= 0 then X else "
      "0 - X end.\n"
      "a(A, X) -o a(A, sq(abs(X))).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().functions.size(), 2u);
  const Function& sq = l.p().functions[0];
  BOOST_TEST(sq.params == std::vector<TypeId>{TypeTable::kInt});
  BOOST_TEST(opNames(sq.block) == "MULI MOV RET");
  BOOST_TEST(only(l.rule(1), Opcode::CALLF).size() == 2u);
}

BOOST_AUTO_TEST_CASE(heads_send_delay_act_and_create) {
  Lowered l(
      "type linear a(node, node).\ntype linear b(node, int).\ntype linear c(node).\n"
      "a(A, B) -o b(B, 1), b(A, 2)@+2s, b(@0, 3)@+5ms, setcolor(A, 1, 2, 3), write-string(B, \"hi\"),\n"
      "  exists N. (c(N), b(A, 4)), stop-program(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(1);
  BOOST_TEST(only(r, Opcode::SEND).size() == 2u);  // b(B, 1), c(N)
  const auto delayed = only(r, Opcode::SEND_DELAY);
  BOOST_REQUIRE_EQUAL(delayed.size(), 2u);
  BOOST_TEST(delayed[0].operands.at(2) == 2000u);
  BOOST_TEST(delayed[1].operands.at(2) == 5u);
  BOOST_TEST(only(r, Opcode::ACTION).size() == 2u);
  BOOST_TEST(only(r, Opcode::NEWNODE).size() == 1u);
  BOOST_TEST(only(r, Opcode::DERIVE).size() == 1u);  // b(A, 4)
  BOOST_TEST(only(r, Opcode::STOP_PROGRAM).size() == 1u);
  BOOST_TEST(l.p().strings == std::vector<std::string>{"hi"});
}

BOOST_AUTO_TEST_CASE(comprehension_consumes_with_cfire) {
  Lowered l(
      "type linear go(node).\ntype linear v(node, int).\ntype linear w(node, int).\n"
      "go(A) -o {X | v(A, X) | w(A, X)}, go(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(1);
  BOOST_TEST(opNames(r) == "HOST ITER ITER LOAD DERIVE CFIRE NEXT FIRE NEXT RET");
  const auto flags = iterFlags(r);
  BOOST_TEST(flags.at(0) == std::uint32_t(kIterLinear));  // go is re-derived: kept
  BOOST_TEST(flags.at(1) == std::uint32_t(kIterLinear | kIterConsume | kIterConsumableClass));
  BOOST_TEST(only(r, Opcode::CFIRE).at(0).operands.at(0) == 1u);
}

BOOST_AUTO_TEST_CASE(aggregates_accumulate_and_derive_once) {
  Lowered l(
      "type linear go(node).\ntype linear v(node, int).\ntype linear n(node, int).\n"
      "type linear s(node, list int).\ntype linear f(node, float).\ntype linear g(node, float).\n"
      "go(A) -o [count => C | X | v(A, X) | n(A, C)].\n"
      "go(A) -o [collect => L | v(A, L) | s(A, L)].\n"
      "go(A) -o [sum => S | f(A, S) | g(A, S)].\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  // (count reads no field: its X is written once in the rule and not loaded)
  BOOST_TEST(opNames(l.rule(1)) ==
             "HOST ITER MOVI MOVI ITER ADDI CFIRE NEXT DERIVE FIRE NEXT "
             "HOST ITER NIL ITER LOAD CONS CFIRE NEXT DERIVE FIRE NEXT "
             "HOST ITER MOVF ITER LOAD ADDF CFIRE NEXT DERIVE FIRE NEXT RET");
}

BOOST_AUTO_TEST_CASE(conditions_short_circuit) {
  Lowered l(
      "type linear a(node, int, list int).\ntype linear b(node).\n"
      "a(A, X, L), X > 1 && (X < 5 || X in L), L <> [] -o b(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(1);
  BOOST_TEST(only(r, Opcode::JF).size() == 2u);
  BOOST_TEST(only(r, Opcode::JT).size() == 1u);
  BOOST_TEST(only(r, Opcode::JNIL).size() == 1u);
  BOOST_TEST(only(r, Opcode::CALL).at(0).operands.at(1) == 51u);  // lexists
}

BOOST_AUTO_TEST_CASE(bytecode_round_trip) {
  Lowered l(
      "type linear a(node, int).\ntype route e(node, node).\n!e(@0, @1).\na(@0, 3).\n"
      "a(A, N), !e(A, B), N > 0 -o a(B, N - 1).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const std::vector<std::uint8_t> bytes = writeBytecode(l.p());
  const std::unique_ptr<Program> back = readBytecode(bytes.data(), bytes.size());
  BOOST_TEST(back->rules.size() == l.p().rules.size());
  BOOST_TEST(back->rules.at(1).block.code == l.rule(1).code);
}

BOOST_AUTO_TEST_CASE(unsupported_constructs_are_errors) {
  Lowered data("type edge(node, node).\ndata stanford-snap \"g.txt\".\n");
  BOOST_TEST(!data.program);
  BOOST_TEST(data.errors().find("t.meld:2:1: error: cannot read the data file") != std::string::npos);
  // Every built-in of §5.6 is implemented: the last ones to come compile.
  Lowered builtin("type linear a(node, list int).\na(A, L) -o a(A, degeneratevector(1, 2)).\n");
  BOOST_TEST(builtin.program, builtin.errors());
}

BOOST_AUTO_TEST_CASE(variable_axioms_of_a_subtype_only_on_its_nodes) {
  // @0 is red (home of tag), @1 a plain node: literal order @0, @1 -> @1 = 0, @0 = 1
  Lowered l(
      "node red.\ntype linear tag(red, int).\ntype linear other(node).\n"
      "tag(@0, 1).\nother(@1).\ntag(X, 5).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r0 = l.rule(0);
  BOOST_TEST(opNames(r0) == "ITER AXIOMS HOST MOVN EQ JT JMP MOVI DERIVE FIRE NEXT RET");
  BOOST_TEST(only(r0, Opcode::MOVN).at(0).operands.at(1) == 1u);
}

BOOST_AUTO_TEST_CASE(custom_aggregate_folds_with_the_function) {
  Lowered l(
      "type linear go(node).\ntype linear v(node, int).\ntype linear r(node, int).\n"
      "fun mx(int A, int B) : int = if A > B then A else B end.\n"
      "go(A) -o [custom mx 0 => M | v(A, M) | r(A, M)].\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(opNames(l.rule(1)) == "HOST ITER MOVI MOV ITER LOAD CALLF MOV CFIRE NEXT DERIVE FIRE NEXT RET");
}
