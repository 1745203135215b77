// The rule engine on hand-assembled programs (independent of meldc): firing order, the linear-
// ancestor rule of §6.4.3, deferred visibility (§6.4.4), persistent processes (§6.5) and sends.
#define BOOST_TEST_MODULE vm_machine
#include <boost/test/unit_test.hpp>

#include "bytecode_fixture.hpp"
#include "meldvm/arith.hpp"
#include "meldvm/machine.hpp"

using namespace bctest;

namespace {

constexpr TypeId kI = TypeTable::kInt, kN = TypeTable::kNode;

// Program with nodes 0..nodes-1, `_init`, rule 0, and an axiom block per node made by `axioms`.
std::unique_ptr<Program> base(std::uint32_t nodes) {
  auto p = std::make_unique<Program>();
  p->initPredicate = pred(*p, "_init", {}, true);
  emit(p->globalsInit, Opcode::RET);
  for (std::uint32_t n = 0; n < nodes; ++n) {
    p->nodeSourceIds.push_back(n);
    p->nodeAxioms.push_back(Program::kNoAxioms);
  }
  Rule r0;
  r0.block.label = "_init -o axioms";
  r0.block.slots = 1;
  r0.bodyPredicates = {p->initPredicate};
  loop(r0.block, Opcode::ITER, {p->initPredicate, 0, kLinConsume | kIterConsumableClass}, [&] {
    emit(r0.block, Opcode::AXIOMS);
    emit(r0.block, Opcode::FIRE, {0});
  });
  emit(r0.block, Opcode::RET);
  p->rules.push_back(std::move(r0));
  return p;
}

// Axioms p(@node, v) for each v (one int field).
void intAxioms(Program& p, NodeId node, PredId pr, std::initializer_list<int> values) {
  CodeBlock ax;
  ax.registerTypes = {kI};
  for (int v : values) {
    emit(ax, Opcode::MOVI, {0, std::uint32_t(v)});
    emit(ax, Opcode::DERIVE, {pr, 1, 0});
  }
  emit(ax, Opcode::RET);
  p.nodeAxioms[node] = std::uint32_t(p.axiomBlocks.size());
  p.axiomBlocks.push_back(std::move(ax));
}

std::string runDump(const Program& p) {
  verifyProgram(p);
  Machine m(p);
  m.run();
  return m.dump();
}

}  // namespace

BOOST_AUTO_TEST_CASE(linear_rule_fires_once_per_fact_and_derived_facts_wait_for_the_run_end) {
  // a(A, N) -o a2(A, N + 1) and a2(A, N) -o c(A, N): a2 facts appear after rule 1's run.
  auto p = base(1);
  const PredId a = pred(*p, "a", {kI}, true), b = pred(*p, "b", {kI}, true);
  intAxioms(*p, 0, a, {1, 2, 3});
  Rule r;
  r.block.slots = 1;
  r.block.registerTypes = {kI, kI, kI};
  r.bodyPredicates = {a};
  loop(r.block, Opcode::ITER, {a, 0, kLinConsume | kIterConsumableClass}, [&] {
    emit(r.block, Opcode::LOAD, {0, 0, 0});
    emit(r.block, Opcode::MOVI, {1, 10});
    emit(r.block, Opcode::MULI, {2, 0, 1});
    emit(r.block, Opcode::DERIVE, {b, 1, 2});
    emit(r.block, Opcode::FIRE, {0});
  });
  emit(r.block, Opcode::RET);
  p->rules.push_back(std::move(r));
  BOOST_TEST(runDump(*p) == "0\nb(10)\nb(20)\nb(30)\n");
}

BOOST_AUTO_TEST_CASE(pairs_of_one_predicate_follow_the_linear_ancestor_rule) {
  // update(A, X), update(A, Y) -o s(A, X + Y): four facts give the pairs 1+2 and 3+4 (§6.4.3).
  auto p = base(1);
  const PredId u = pred(*p, "update", {kI}, true), s = pred(*p, "s", {kI}, true);
  intAxioms(*p, 0, u, {1, 2, 3, 4});
  Rule r;
  r.block.slots = 2;
  r.block.registerTypes = {kI, kI, kI};
  r.bodyPredicates = {u};
  const std::uint32_t consume = kLinConsume | kIterConsumableClass;
  loop(r.block, Opcode::ITER, {u, 0, consume}, [&] {
    emit(r.block, Opcode::LOAD, {0, 0, 0});
    loop(r.block, Opcode::ITER, {u, 1, consume | kIterReturnOnFire}, [&] {
      emit(r.block, Opcode::LOAD, {1, 0, 1});
      emit(r.block, Opcode::ADDI, {2, 0, 1});
      emit(r.block, Opcode::DERIVE, {s, 1, 2});
      emit(r.block, Opcode::FIRE, {0});
    });
  });
  emit(r.block, Opcode::RET);
  p->rules.push_back(std::move(r));
  BOOST_TEST(runDump(*p) == "0\ns(3)\ns(7)\n");
}

BOOST_AUTO_TEST_CASE(in_place_update_is_visible_to_the_continuing_loops) {
  // a(A, N1), a(A, N2) -o a(A, N1 * 100 + N2) as an update of the outer fact: 802 (§6.4.5).
  auto p = base(1);
  const PredId a = pred(*p, "a", {kI}, true);
  intAxioms(*p, 0, a, {1, 2, 3, 4});
  Rule r;
  r.block.slots = 2;
  r.block.registerTypes = {kI, kI, kI, kI};
  r.bodyPredicates = {a};
  loop(r.block, Opcode::ITER, {a, 0, kIterLinear | kIterConsumableClass}, [&] {
    emit(r.block, Opcode::LOAD, {0, 0, 0});
    loop(r.block, Opcode::ITER, {a, 1, kLinConsume | kIterConsumableClass | kIterReturnOnFire}, [&] {
      emit(r.block, Opcode::LOAD, {1, 0, 1});
      emit(r.block, Opcode::MOVI, {2, 100});
      emit(r.block, Opcode::MULI, {3, 0, 2});
      emit(r.block, Opcode::ADDI, {3, 3, 1});
      emit(r.block, Opcode::UPDATE, {0, 0, 1, 3});
      emit(r.block, Opcode::FIRE, {0});
    });
  });
  emit(r.block, Opcode::RET);
  p->rules.push_back(std::move(r));
  BOOST_TEST(runDump(*p) == "0\na(802)\n");
}

BOOST_AUTO_TEST_CASE(persistent_process_counts_copies_and_sends_between_nodes) {
  // !tapped(A), !neighbor(A, B) -o !tapped(B) on two mutual neighbours (§6.5 tap_propagate).
  auto p = base(2);
  const PredId tapped = pred(*p, "tapped", {}, false);
  const PredId nb = pred(*p, "neighbor", {kN}, false, [](PredicateDesc& d) { d.route = true; });
  for (NodeId n = 0; n < 2; ++n) {
    CodeBlock ax;
    ax.registerTypes = {kN};
    emit(ax, Opcode::MOVN, {0, 1 - n});
    emit(ax, Opcode::DERIVE, {nb, 1, 0});
    if (n == 0) emit(ax, Opcode::DERIVE, {tapped, 0});
    emit(ax, Opcode::RET);
    p->nodeAxioms[n] = std::uint32_t(p->axiomBlocks.size());
    p->axiomBlocks.push_back(std::move(ax));
  }
  // Triggered by tapped: loop over neighbor; triggered by neighbor: loop over tapped.
  Process onTapped{tapped, {}};
  onTapped.block.slots = 2;
  onTapped.block.registerTypes = {kN};
  loop(onTapped.block, Opcode::ITER, {nb, 1, 0}, [&] {
    emit(onTapped.block, Opcode::LOAD, {1, 0, 0});
    emit(onTapped.block, Opcode::SEND, {tapped, 0, 0});
    emit(onTapped.block, Opcode::FIRE, {1});
  });
  emit(onTapped.block, Opcode::RET);
  Process onNeighbor{nb, {}};
  onNeighbor.block.slots = 2;
  onNeighbor.block.registerTypes = {kN};
  emit(onNeighbor.block, Opcode::LOAD, {0, 0, 0});
  loop(onNeighbor.block, Opcode::ITER, {tapped, 1, 0}, [&] {
    emit(onNeighbor.block, Opcode::SEND, {tapped, 0, 0});
    emit(onNeighbor.block, Opcode::FIRE, {1});
  });
  emit(onNeighbor.block, Opcode::RET);
  p->processes.push_back(std::move(onTapped));
  p->processes.push_back(std::move(onNeighbor));
  // Node 0 runs first and taps node 1; node 1 sends it back (counted once more at node 0).
  BOOST_TEST(runDump(*p) == "0\n!neighbor(@1)\n!tapped()\n!tapped()\n1\n!neighbor(@0)\n!tapped()\n");
}

BOOST_AUTO_TEST_CASE(a_node_literal_outside_the_node_table_is_refused_before_the_run) {
  // Node values come from literals (checked here), the host, `exists` and facts: a damaged file
  // cannot make the VM send to, or ask the scheduler about, a node that never existed.
  auto p = base(1);
  const PredId a = pred(*p, "a", {}, true);
  CodeBlock ax;
  ax.registerTypes = {kN};
  emit(ax, Opcode::MOVN, {0, 5});
  emit(ax, Opcode::SEND, {a, 0, 0});
  emit(ax, Opcode::RET);
  p->nodeAxioms[0] = 0;
  p->axiomBlocks.push_back(std::move(ax));
  BOOST_CHECK_EXCEPTION(verifyProgram(*p), BytecodeError, [](const BytecodeError& e) {
    return std::string(e.what()).find("MOVN: node @5 is not one of the program's 1 nodes") != std::string::npos;
  });
}
