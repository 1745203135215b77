// Back end: match plans of rules (§6.4.3), reuse and in-place updates (§6.4.5), persistent rules
// (§6.5), rule merging (§6.15).
#define BOOST_TEST_MODULE meldc_lower_rules
#include <boost/test/unit_test.hpp>

#include "lower_support.hpp"

using meldvm::Opcode;
using namespace meldvm;

namespace {
constexpr std::uint32_t kLin = kIterLinear, kCons = kIterConsume, kRet = kIterReturnOnFire,
                        kClass = kIterConsumableClass;
}

BOOST_AUTO_TEST_CASE(linear_ancestor_sets_return_on_fire) {
  Lowered l("type linear update(node).\ntype linear x(node).\nupdate(A), update(A) -o x(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().rules.size(), 2u);
  const auto flags = iterFlags(l.rule(1));
  BOOST_REQUIRE_EQUAL(flags.size(), 2u);
  BOOST_TEST(flags[0] == (kLin | kCons | kClass));
  BOOST_TEST(flags[1] == (kLin | kCons | kClass | kRet));
  BOOST_TEST(only(l.rule(1), Opcode::FIRE).at(0).operands.at(0) == 0u);
}

BOOST_AUTO_TEST_CASE(persistent_outer_loop_does_not_return_on_fire) {
  Lowered l(
      "type edge(node, node).\ntype linear a(node, int).\ntype linear b(node, int).\n"
      "!edge(A, B), a(A, N) -o b(B, N).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto flags = iterFlags(l.rule(1));
  BOOST_REQUIRE_EQUAL(flags.size(), 2u);
  BOOST_TEST(flags[0] == 0u);
  BOOST_TEST(flags[1] == (kLin | kCons | kClass));
  // b goes to B, another node
  BOOST_TEST(only(l.rule(1), Opcode::SEND).size() == 1u);
  BOOST_TEST(only(l.rule(1), Opcode::DERIVE).empty());
}

BOOST_AUTO_TEST_CASE(rederived_fact_is_kept_and_not_derived) {
  Lowered l("type linear visit(node).\ntype linear visited(node).\nvisit(A), visited(A) -o visited(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto flags = iterFlags(l.rule(1));
  BOOST_REQUIRE_EQUAL(flags.size(), 2u);
  BOOST_TEST(flags[0] == (kLin | kCons | kClass));
  BOOST_TEST(flags[1] == (kLin | kRet));  // visited: kept, not consumable
  BOOST_TEST(only(l.rule(1), Opcode::DERIVE).empty());
}

BOOST_AUTO_TEST_CASE(reused_subgoal_is_not_consumed) {
  Lowered l(
      "type linear a(node).\ntype linear t(node, int).\ntype linear b(node).\n$t(A, _), a(A) -o b(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto flags = iterFlags(l.rule(1));
  BOOST_TEST(flags[0] == kLin);
  BOOST_TEST(flags[1] == (kLin | kCons | kClass));  // no consumable linear loop encloses it
}

BOOST_AUTO_TEST_CASE(two_facts_of_one_predicate_update_the_outermost) {
  Lowered l("type linear a(node, int).\na(A, N1), a(A, N2) -o a(A, N1 * 100 + N2).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto flags = iterFlags(l.rule(1));
  BOOST_REQUIRE_EQUAL(flags.size(), 2u);
  BOOST_TEST(flags[0] == (kLin | kClass));  // updated: not consumed, still consumable class
  BOOST_TEST(flags[1] == (kLin | kCons | kClass | kRet));
  const auto updates = only(l.rule(1), Opcode::UPDATE);
  BOOST_REQUIRE_EQUAL(updates.size(), 1u);
  BOOST_TEST(updates[0].operands.at(0) == 0u);  // slot
  BOOST_TEST(updates[0].operands.at(1) == 0u);  // flags
  BOOST_TEST(updates[0].operands.at(2) == 1u);  // one register
  BOOST_TEST(only(l.rule(1), Opcode::DERIVE).empty());
}

BOOST_AUTO_TEST_CASE(single_fact_update_moves_to_back_unless_outermost) {
  Lowered inner("type linear a(node, int).\ntype linear go(node).\ngo(A), a(A, 2) -o a(A, 20).\n");
  BOOST_REQUIRE_MESSAGE(inner.ok(), inner.errors());
  auto u = only(inner.rule(1), Opcode::UPDATE);
  BOOST_REQUIRE_EQUAL(u.size(), 1u);
  BOOST_TEST(u[0].operands.at(0) == 1u);
  BOOST_TEST(u[0].operands.at(1) == std::uint32_t(kUpdateMoveToBack));
  BOOST_TEST(iterFlags(inner.rule(1)).at(1) == (kLin | kClass | kRet));

  Lowered outer("type linear a(node, int).\ntype linear go(node).\na(A, 2), go(A) -o a(A, 20).\n");
  BOOST_REQUIRE_MESSAGE(outer.ok(), outer.errors());
  u = only(outer.rule(1), Opcode::UPDATE);
  BOOST_REQUIRE_EQUAL(u.size(), 1u);
  BOOST_TEST(u[0].operands.at(0) == 0u);
  BOOST_TEST(u[0].operands.at(1) == 0u);
}

BOOST_AUTO_TEST_CASE(conditional_head_is_not_an_update) {
  Lowered l("type linear a(node, int).\na(A, N) -o (if N > 1 then a(A, N - 1) otherwise 1 end).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(only(l.rule(1), Opcode::UPDATE).empty());
  BOOST_TEST(only(l.rule(1), Opcode::DERIVE).size() == 1u);
  BOOST_TEST(iterFlags(l.rule(1)).at(0) == (kLin | kCons | kClass));
}

BOOST_AUTO_TEST_CASE(persistent_rules_become_processes) {
  Lowered l(
      "type edge(node, node).\ntype reach(node).\ntype linear t(node).\n"
      "!edge(A, B), !reach(A) -o !reach(B).\n"
      "t(A) -o !reach(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().rules.size(), 2u);  // rule 0 and the t rule
  BOOST_REQUIRE_EQUAL(l.p().processes.size(), 2u);
  BOOST_TEST(l.p().processes[0].trigger == l.pred("edge"));
  BOOST_TEST(l.p().processes[1].trigger == l.pred("reach"));
  // the trigger is slot 0, read without a loop; the other subgoal is the one loop (slot 1)
  const auto code = decode(l.p().processes[0].block);
  BOOST_TEST(opNames(l.p().processes[0].block) == "HOST LOAD ITER SEND FIRE NEXT RET");
  BOOST_TEST(code.at(1).operands.at(0) == 0u);
  BOOST_TEST(code.at(2).operands.at(1) == 1u);
  BOOST_TEST(l.p().processes[0].block.slots == 2u);
}

BOOST_AUTO_TEST_CASE(rule_with_comprehension_stays_numbered) {
  Lowered l(
      "type edge(node, node).\ntype linear v(node).\ntype go(node).\n"
      "!go(A) -o {B | !edge(A, B) | v(B)}.\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(l.p().rules.size() == 2u);
  BOOST_TEST(l.p().processes.empty());
}

BOOST_AUTO_TEST_CASE(consecutive_rules_with_same_body_predicates_merge) {
  Lowered l(
      "type linear a(node, int).\ntype linear b(node).\ntype linear c(node).\n"
      "a(A, 1) -o b(A).\na(A, N), N > 1 -o c(A).\nb(A) -o c(A).\na(A, _) -o .\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().rules.size(), 4u);
  BOOST_TEST(only(l.rule(1), Opcode::FIRE).size() == 2u);  // two original rules in one block
  BOOST_TEST(l.p().rules[1].bodyPredicates == std::vector<PredId>{l.pred("a")});
  BOOST_TEST(l.p().rules[2].bodyPredicates == std::vector<PredId>{l.pred("b")});
  BOOST_TEST(only(l.rule(3), Opcode::FIRE).size() == 1u);
}

BOOST_AUTO_TEST_CASE(failing_tests_jump_to_the_innermost_next) {
  Lowered l(
      "type linear a(node, int).\ntype linear b(node, int).\ntype linear c(node).\n"
      "a(A, N), b(A, 3), N > 2 -o c(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto code = decode(l.rule(1));
  std::vector<std::uint32_t> nexts;
  for (const Instr& i : code)
    if (i.op == Opcode::NEXT) nexts.push_back(i.at);
  BOOST_REQUIRE_EQUAL(nexts.size(), 2u);
  for (const Instr& i : code) {
    if (i.op == Opcode::TEST) BOOST_TEST(i.operands.at(3) == nexts[0]);  // b's NEXT (innermost)
    // N > 2 is tested as soon as N is bound: inside a's loop, before b's
    if (i.op == Opcode::JF) BOOST_TEST(i.operands.at(1) == nexts[1]);
  }
}

BOOST_AUTO_TEST_CASE(constraint_before_any_loop_jumps_to_the_end) {
  Lowered l("type linear a(node, int).\nconst k = 3.\na(A, N), k > 2 -o .\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto code = decode(l.rule(1));
  const auto jf = only(l.rule(1), Opcode::JF);
  BOOST_REQUIRE_EQUAL(jf.size(), 1u);
  BOOST_TEST(jf[0].at < only(l.rule(1), Opcode::ITER).at(0).at);
  BOOST_TEST(jf[0].operands.at(1) == code.back().at);  // the final RET
}

BOOST_AUTO_TEST_CASE(selectors_iterate_sorted) {
  Lowered l(
      "type linear c(node, int).\ntype linear t(node).\ntype linear r(node, int).\n"
      "[:min V | t(A), c(A, V)] -o r(A, V).\n[:random V | c(A, V)] -o r(A, V).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const auto sorted = only(l.rule(1), Opcode::ITER_SORTED);
  BOOST_REQUIRE_EQUAL(sorted.size(), 1u);
  BOOST_TEST(sorted[0].operands.at(0) == l.pred("c"));
  BOOST_TEST(sorted[0].operands.at(3) == 0u);                       // field of V
  BOOST_TEST((decode(l.rule(1)).at(1).op == Opcode::ITER_SORTED));  // selector subgoal first
  const auto random = only(l.rule(2), Opcode::ITER_SORTED);
  BOOST_REQUIRE_EQUAL(random.size(), 1u);
  BOOST_TEST((random[0].operands.at(2) & kIterRandom) != 0u);
}

BOOST_AUTO_TEST_CASE(indexed_predicates_are_matched_last) {
  Lowered l(
      "type linear v(node, int, int).\ntype linear k(node, int).\ntype linear r(node).\n"
      "index v/2.\nv(A, K, _), k(A, K) -o r(A).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_REQUIRE_EQUAL(l.p().indexes.size(), 1u);
  BOOST_TEST(l.p().indexes[0].predicate == l.pred("v"));
  BOOST_TEST(l.p().indexes[0].field == 0u);
  const auto iters = only(l.rule(1), Opcode::ITER);
  BOOST_REQUIRE_EQUAL(iters.size(), 1u);
  BOOST_TEST(iters.at(0).operands.at(0) == l.pred("k"));
  // K is bound by k when v is matched: the index finds v's facts with that key (ITER_KEY field 0).
  const auto keyed = only(l.rule(1), Opcode::ITER_KEY);
  BOOST_REQUIRE_EQUAL(keyed.size(), 1u);
  BOOST_TEST(keyed.at(0).operands.at(0) == l.pred("v"));
  BOOST_TEST(keyed.at(0).operands.at(3) == 0u);
  BOOST_TEST(only(l.rule(1), Opcode::TEST).empty());  // no test left for the key
}

BOOST_AUTO_TEST_CASE(list_patterns_destructure) {
  Lowered l(
      "type linear a(node, list int).\ntype linear b(node, int, list int).\n"
      "a(A, [X | L]) -o b(A, X, L).\na(A, []) -o .\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(opNames(l.rule(1)) ==
             "HOST ITER LOAD JNIL HEAD TAIL DERIVE FIRE NEXT HOST ITER LOAD JNOTNIL FIRE NEXT RET");
}

// A variable written once in the whole rule binds nothing that is read: no LOAD. One that joins
// two subgoals, or that a head, a constraint or a comprehension reads, is loaded.
BOOST_AUTO_TEST_CASE(variables_written_once_are_not_loaded) {
  Lowered l(
      "type linear a(node, node, int).\ntype linear b(node, node, int).\ntype linear c(node, int).\n"
      "a(A, B, X), b(A, B, Y) -o c(A, Y).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  // a's B (the join) and b's Y (the head) are loaded; a's X is not.
  BOOST_TEST(opNames(l.rule(1)) == "HOST ITER LOAD ITER TEST LOAD DERIVE FIRE NEXT NEXT RET");

  Lowered used(
      "type linear a(node, int).\ntype linear b(node, int).\ntype linear c(node, int).\n"
      "type linear d(node, int).\ntype e(node, int).\n"
      "a(A, X), b(A, Y), X > 2 -o c(A, Y).\n"
      "d(A, X) -o {Z | !e(A, Z), Z > X | c(A, Z)}.\n");
  BOOST_REQUIRE_MESSAGE(used.ok(), used.errors());
  BOOST_TEST(only(used.rule(1), Opcode::LOAD).size() == 2u);  // X (the constraint reads it), Y
  BOOST_TEST(only(used.rule(2), Opcode::LOAD).size() == 2u);  // X (the comprehension reads it), Z

  // A comprehension's declared variable that its body writes once and nothing reads.
  Lowered declared(
      "type linear a(node, int).\ntype e(node, node, int).\ntype linear c(node, node).\n"
      "a(A, X) -o {B, W | !e(A, B, W) | c(B, A)}.\n");
  BOOST_REQUIRE_MESSAGE(declared.ok(), declared.errors());
  BOOST_TEST(opNames(declared.rule(1)) == "HOST ITER ITER LOAD SEND CFIRE NEXT FIRE NEXT RET");
}
