// Back end, thread predicates (§6.12, one VM thread): the predicate table, rule 1
// (`_init_thread -o thread axioms`, §6.2), thread loops (kIterThread, the home bound or checked with
// THREAD), SEND_THREAD in heads, rules and processes that run at the thread node.
#define BOOST_TEST_MODULE meldc_lower_threads
#include <boost/test/unit_test.hpp>

#include "lower_support.hpp"

using meldvm::Opcode;
using namespace meldvm;

namespace {

constexpr std::uint32_t kInitFlags = kIterLinear | kIterConsume | kIterConsumableClass;

const char* const kBasic =
    "type linear p(node).\ntype linear q(node, thread).\ntype linear work(thread, int).\n"
    "p(@0).\nwork(T, 3).\n"
    "p(A), !leader-thread(T, L) -o q(A, L).\n";

}  // namespace

BOOST_AUTO_TEST_CASE(thread_predicates_in_the_table) {
  Lowered l(kBasic);
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const PredicateTable& preds = l.p().predicates;
  // _init, the built-ins in table order (_init_thread always, leader-thread as mentioned), then
  // the declarations.
  BOOST_TEST(preds.size() == 6u);
  BOOST_TEST(preds[0].name == "_init");
  BOOST_TEST(!preds[0].thread);
  BOOST_TEST(preds[1].name == "_init_thread");
  BOOST_TEST(preds[1].linear);
  BOOST_TEST(preds[1].thread);
  BOOST_TEST(preds[1].arity() == 0u);
  const PredicateDesc& leader = preds[l.pred("leader-thread")];
  BOOST_TEST(leader.thread);
  BOOST_TEST(leader.persistent());
  BOOST_TEST(leader.compact);
  BOOST_TEST(leader.fields == std::vector<TypeId>{TypeTable::kThread});
  const PredicateDesc& work = preds[l.pred("work")];
  BOOST_TEST(work.thread);
  BOOST_TEST(work.linear);
  BOOST_TEST(work.fields == std::vector<TypeId>{TypeTable::kInt});  // home excluded
  BOOST_TEST(!preds[l.pred("q")].thread);                           // a node predicate with a thread field
  BOOST_TEST(preds.find("thread-list") == preds.size());            // not mentioned
  BOOST_TEST(preds.find("other-thread") == preds.size());
}

BOOST_AUTO_TEST_CASE(special_thread_facts_have_their_types) {
  Lowered l(
      "type linear a(node).\na(@0).\n"
      "a(A), !thread-list(T, L), !other-thread(T, T2, I) -o 1.\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const PredicateTable& preds = l.p().predicates;
  BOOST_TEST(preds.find("_init_thread") != preds.size());  // the built-ins are thread predicates
  const PredicateDesc& list = preds[l.pred("thread-list")];
  BOOST_TEST((list.thread && list.compact && list.persistent()));
  BOOST_REQUIRE(list.fields.size() == 1u);
  BOOST_TEST((l.p().types.kind(list.fields[0]) == TypeKind::List));
  BOOST_TEST(l.p().types.element(list.fields[0]) == TypeTable::kThread);
  const PredicateDesc& other = preds[l.pred("other-thread")];
  BOOST_TEST((other.thread && other.compact && other.persistent()));
  BOOST_TEST(other.fields == (std::vector<TypeId>{TypeTable::kThread, TypeTable::kInt}));
}

BOOST_AUTO_TEST_CASE(no_thread_predicates_no_rule_1) {
  Lowered l("type linear a(node, thread).\na(@0, @thread).\na(A, T) -o 1.\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(l.p().predicates.find("_init_thread") == l.p().predicates.size());
  BOOST_TEST(l.p().rules.size() == 2u);
  BOOST_TEST(l.p().rules.at(1).block.label == "a(A, T) -o 1.");
}

BOOST_AUTO_TEST_CASE(rule_1_instantiates_the_thread_axioms) {
  Lowered l(kBasic);
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(l.p().rules.size() == 3u);  // rule 0, rule 1, the user rule
  // Rule 0: only the node's axioms; the thread variable axiom is not instantiated per node.
  BOOST_TEST(opNames(l.rule(0)) == "ITER AXIOMS FIRE NEXT RET");
  const Rule& r1 = l.p().rules.at(1);
  BOOST_TEST(r1.bodyPredicates == std::vector<PredId>{l.pred("_init_thread")});
  BOOST_TEST(opNames(r1.block) == "ITER THREAD MOVI SEND_THREAD FIRE NEXT RET");
  const Instr iter = only(r1.block, Opcode::ITER).at(0);
  BOOST_TEST(iter.operands.at(0) == l.pred("_init_thread"));
  BOOST_TEST(iter.operands.at(2) == (kInitFlags | kIterThread));
  const Instr thread = only(r1.block, Opcode::THREAD).at(0);
  const Instr send = only(r1.block, Opcode::SEND_THREAD).at(0);
  BOOST_TEST(send.operands.at(0) == l.pred("work"));
  BOOST_TEST(send.operands.at(1) == thread.operands.at(0));  // the home: the running thread
  BOOST_TEST(send.operands.at(2) == 1u);                     // one argument
  BOOST_TEST(l.rule(2).label == "p(A), !leader-thread(T, L) -o q(A, L).");
}

BOOST_AUTO_TEST_CASE(rule_1_exists_without_thread_axioms) {
  // Rule numbering (§6.4.1) does not depend on the presence of thread axioms.
  Lowered ok("type linear a(node).\ntype linear w(thread, int).\na(@0).\na(A), w(T, N) -o w(T, N + 1).\n");
  BOOST_REQUIRE_MESSAGE(ok.ok(), ok.errors());
  BOOST_TEST(ok.p().rules.size() == 3u);
  BOOST_TEST(opNames(ok.rule(1)) == "ITER THREAD FIRE NEXT RET");
}

BOOST_AUTO_TEST_CASE(thread_loops_carry_the_thread_flag_and_bind_the_home) {
  Lowered l(kBasic);
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(2);
  BOOST_TEST(opNames(r) == "HOST ITER ITER THREAD LOAD DERIVE FIRE NEXT NEXT RET");
  BOOST_TEST(iterFlags(r) == (std::vector<std::uint32_t>{kInitFlags, kIterReturnOnFire | kIterThread}));
  BOOST_TEST(l.p().rules.at(2).bodyPredicates == (std::vector<PredId>{l.pred("p"), l.pred("leader-thread")}));
}

BOOST_AUTO_TEST_CASE(a_bound_thread_home_is_compared_with_the_running_thread) {
  Lowered l(
      "type linear a(node, thread).\ntype linear w(thread, int).\na(@0, @thread).\n"
      "a(A, T), w(T, N) -o a(A, T).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(2);
  // (w's N is written once in the rule: not loaded)
  BOOST_TEST(opNames(r) == "HOST ITER LOAD ITER THREAD EQ JF FIRE NEXT NEXT RET");
  const Instr eq = only(r, Opcode::EQ).at(0);
  BOOST_TEST(eq.operands.at(1) == only(r, Opcode::LOAD).at(0).operands.at(2));  // T from a
  BOOST_TEST(eq.operands.at(2) == only(r, Opcode::THREAD).at(0).operands.at(0));
  BOOST_TEST(eq.operands.at(3) == TypeTable::kThread);
  // A failed comparison goes on with the next candidate of this (the w) loop.
  const std::vector<Instr> all = decode(r);
  const Instr jf = only(r, Opcode::JF).at(0);
  const Instr& innerNext = all.at(all.size() - 3);
  BOOST_TEST((innerNext.op == Opcode::NEXT));
  BOOST_TEST(jf.operands.at(1) == innerNext.at);
}

BOOST_AUTO_TEST_CASE(thread_heads_send_to_the_thread) {
  Lowered l(
      "type linear job(node, int).\ntype linear w(thread, int).\njob(@0, 2).\n"
      "job(A, N), T = @thread -o w(T, N).\n"
      "job(A, N) -o w(@thread, N + 1).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(2);  // both rules share their body predicates: merged
  BOOST_TEST(only(r, Opcode::DERIVE).empty());
  BOOST_TEST(only(r, Opcode::SEND).empty());
  const std::vector<Instr> sends = only(r, Opcode::SEND_THREAD);
  BOOST_REQUIRE(sends.size() == 2u);
  const std::vector<Instr> threads = only(r, Opcode::THREAD);
  BOOST_REQUIRE(threads.size() == 2u);
  for (size_t i = 0; i < 2; ++i) {
    BOOST_TEST(sends[i].operands.at(0) == l.pred("w"));
    BOOST_TEST(sends[i].operands.at(1) == threads[i].operands.at(0));
  }
}

BOOST_AUTO_TEST_CASE(rules_with_only_thread_facts_have_no_host) {
  Lowered l(
      "type linear w(thread, int).\ntype linear v(thread, int).\nw(T, 0).\n"
      "w(T, N), v(T, M), N < 3 -o w(T, N + M).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(l.p().nodeSourceIds.empty());  // no normal nodes at all
  const CodeBlock& r = l.rule(2);
  BOOST_TEST(only(r, Opcode::HOST).empty());
  BOOST_TEST(iterFlags(r) == (std::vector<std::uint32_t>{kInitFlags | kIterThread,
                                                         kInitFlags | kIterThread | kIterReturnOnFire}));
  BOOST_TEST(only(r, Opcode::SEND_THREAD).size() == 1u);
  BOOST_TEST(only(r, Opcode::EQ).size() == 1u);  // v's home T compared with w's
}

BOOST_AUTO_TEST_CASE(processes_triggered_by_thread_facts) {
  Lowered l(
      "type total(thread, int).\ntype linear a(node).\na(@0).\n"
      "!thread-list(T, L), !other-thread(T, T2, I) -o !total(T, I).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  BOOST_TEST(l.p().rules.size() == 2u);  // rules 0 and 1, the rule is persistent
  BOOST_REQUIRE(l.p().processes.size() == 2u);
  for (const Process& p : l.p().processes) {
    BOOST_TEST(l.p().predicates[p.trigger].thread);
    // Slot 0 (the trigger) is bound by the engine; its home is the running thread.
    const std::vector<Instr> all = decode(p.block);
    BOOST_TEST((all.at(0).op == Opcode::THREAD));
    BOOST_TEST(iterFlags(p.block) == std::vector<std::uint32_t>{kIterThread});
    BOOST_TEST(only(p.block, Opcode::SEND_THREAD).at(0).operands.at(1) == all.at(0).operands.at(0));
  }
}

BOOST_AUTO_TEST_CASE(thread_facts_round_trip_through_bytecode) {
  Lowered l(kBasic);
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const std::vector<std::uint8_t> bytes = writeBytecode(l.p());
  const std::unique_ptr<Program> back = readBytecode(bytes.data(), bytes.size());
  BOOST_TEST(back->predicates[l.pred("work")].thread);
  BOOST_TEST(back->predicates[l.pred("leader-thread")].compact);
  BOOST_TEST(back->rules.at(1).block.code == l.rule(1).code);
}

BOOST_AUTO_TEST_CASE(a_delayed_thread_fact_is_an_error) {
  Lowered l("type linear a(node).\ntype linear w(thread, int).\na(@0).\na(A) -o w(@thread, 1)@+10ms.\n");
  BOOST_TEST(!l.program);
  BOOST_TEST(l.errors().find("t.meld:4:9: error: a delay ('@+...') on the thread fact 'w': thread facts are delivered at once") !=
             std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_thread_fact_rederived_identically_is_kept) {
  // §6.4.5 at the thread: same predicate, same thread variable, same arguments.
  Lowered l(
      "type linear p(node).\ntype linear q(node, int).\ntype linear w(thread, int).\np(@0).\n"
      "p(A), w(T, N) -o w(T, N), q(A, N).\n");
  BOOST_REQUIRE_MESSAGE(l.ok(), l.errors());
  const CodeBlock& r = l.rule(2);
  BOOST_TEST(only(r, Opcode::SEND_THREAD).empty());
  BOOST_TEST(iterFlags(r) ==
             (std::vector<std::uint32_t>{kInitFlags, kIterLinear | kIterReturnOnFire | kIterThread}));
}
