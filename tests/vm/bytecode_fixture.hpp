// Hand-assembled Programs for the bytecode tests: a small one (`_init` and `a(A, N) -o b(A, N+1)`)
// and a full one that fills every table and uses most operand kinds.
#pragma once

#include <bit>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>

#include "meldvm/bytecode.hpp"

namespace bctest {

using namespace meldvm;

// Appends one instruction; returns its word offset.
inline std::size_t emit(CodeBlock& b, Opcode op, std::initializer_list<std::uint32_t> operands = {}) {
  const std::size_t at = b.code.size();
  b.code.push_back(std::uint32_t(op));
  b.code.insert(b.code.end(), operands.begin(), operands.end());
  return at;
}
inline std::uint32_t lo(double d) { return std::uint32_t(std::bit_cast<std::uint64_t>(d)); }
inline std::uint32_t hi(double d) { return std::uint32_t(std::bit_cast<std::uint64_t>(d) >> 32); }

// A loop over `pred` into `slot` around `body`; the exit operand is patched to after the NEXT.
inline void loop(CodeBlock& b, Opcode iter, std::initializer_list<std::uint32_t> operands,
                 const std::function<void()>& body) {
  emit(b, iter, operands);
  const std::size_t exitWord = b.code.size();
  b.code.push_back(0);
  body();
  emit(b, Opcode::NEXT);
  b.code[exitWord] = std::uint32_t(b.code.size());
}

inline PredId pred(Program& p, const std::string& name, std::vector<TypeId> fields, bool linear,
                   void (*tweak)(PredicateDesc&) = nullptr) {
  PredicateDesc d;
  d.name = name;
  d.fields = std::move(fields);
  d.linear = linear;
  if (tweak) tweak(d);
  return p.predicates.add(std::move(d));
}

constexpr std::uint32_t kLinConsume = kIterLinear | kIterConsume;

// Predicates 0 `_init`, 1 `a(node, int)`, 2 `b(node, int)`; rule 0 `_init -o axioms`, rule 1
// `a(A, N) -o b(A, N+1)` (registers r0 node, r1..r3 int; words: ITER 0, LOAD 5, LOAD 9, MOVI 13,
// ADDI 16, DERIVE 20, FIRE 25, NEXT 27, RET 28); one node @0 without axioms.
inline std::unique_ptr<Program> smallProgram() {
  auto p = std::make_unique<Program>();
  const PredId init = pred(*p, "_init", {}, true);
  const PredId a = pred(*p, "a", {TypeTable::kNode, TypeTable::kInt}, true);
  const PredId b = pred(*p, "b", {TypeTable::kNode, TypeTable::kInt}, true);
  p->initPredicate = init;
  p->nodeSourceIds = {0};
  p->nodeAxioms = {Program::kNoAxioms};
  emit(p->globalsInit, Opcode::RET);

  Rule r0;
  r0.block.label = "_init -o axioms";
  r0.block.slots = 1;
  r0.bodyPredicates = {init};
  loop(r0.block, Opcode::ITER, {init, 0, kLinConsume}, [&] {
    emit(r0.block, Opcode::AXIOMS);
    emit(r0.block, Opcode::FIRE, {0});
  });
  emit(r0.block, Opcode::RET);
  p->rules.push_back(std::move(r0));

  Rule r1;
  CodeBlock& c = r1.block;
  c.label = "a(A, N) -o b(A, N+1)";
  c.slots = 1;
  c.registerTypes = {TypeTable::kNode, TypeTable::kInt, TypeTable::kInt, TypeTable::kInt};
  r1.bodyPredicates = {a};
  loop(c, Opcode::ITER, {a, 0, kLinConsume}, [&] {
    emit(c, Opcode::LOAD, {0, 0, 0});
    emit(c, Opcode::LOAD, {0, 1, 1});
    emit(c, Opcode::MOVI, {2, 1});
    emit(c, Opcode::ADDI, {3, 1, 2});
    emit(c, Opcode::DERIVE, {b, 2, 0, 3});
    emit(c, Opcode::FIRE, {0});
  });
  emit(c, Opcode::RET);
  p->rules.push_back(std::move(r1));
  return p;
}

// smallProgram plus types, strings, a global, a function, an extern, two more rules, a process,
// axioms, scheduling options, an index and @arg1.
inline std::unique_ptr<Program> fullProgram() {
  auto p = smallProgram();
  TypeTable& t = p->types;
  const TypeId listInt = t.list(TypeTable::kInt);
  const TypeId pair = t.structOf(std::vector<TypeId>{TypeTable::kInt, TypeTable::kFloat});
  t.set(TypeTable::kString);
  t.array(listInt);
  const PredId c = pred(*p, "c", {TypeTable::kInt, TypeTable::kFloat}, false);
  const PredId edge = pred(*p, "edge", {TypeTable::kNode}, false, [](PredicateDesc& d) { d.route = true; });
  const PredId d = pred(*p, "d", {listInt, pair}, true);
  const PredId act = pred(*p, "act", {TypeTable::kInt}, false, [](PredicateDesc& d) { d.action = true; });
  const PredId total = pred(*p, "total", {TypeTable::kInt}, false, [](PredicateDesc& d) {
    d.aggregate = AggregateKind::Sum;
    d.aggregateField = 0;
  });
  p->strings = {"hi", "with \"quotes\"\n", ""};
  p->globals = {{"limit", TypeTable::kInt}};
  p->globalsInit = {};
  p->globalsInit.registerTypes = {TypeTable::kInt};
  emit(p->globalsInit, Opcode::MOVI, {0, 10});
  emit(p->globalsInit, Opcode::SETGLOBAL, {0, 0});
  emit(p->globalsInit, Opcode::RET);

  Function inc{"inc", {TypeTable::kInt}, TypeTable::kInt, {}};
  inc.block.registerTypes = {TypeTable::kInt, TypeTable::kInt, TypeTable::kInt};
  emit(inc.block, Opcode::MOVI, {2, 1});
  emit(inc.block, Opcode::ADDI, {1, 0, 2});
  emit(inc.block, Opcode::RET);
  p->functions.push_back(std::move(inc));
  p->externs.push_back({"ext", {TypeTable::kInt, TypeTable::kString}, TypeTable::kFloat});

  // c(X, Y), edge(B) -o {send d([inc(X)], :(X, Y)) to B; act(...) at B}
  Rule r2;
  CodeBlock& k = r2.block;
  k.label = "c(X, Y), edge(B) -o d([inc(X)], :(X, Y)) @ B";
  k.slots = 2;
  k.registerTypes = {TypeTable::kInt,
                     TypeTable::kFloat,
                     TypeTable::kInt,
                     TypeTable::kNode,
                     TypeTable::kInt,
                     listInt,
                     pair,
                     TypeTable::kBool,
                     TypeTable::kInt,
                     TypeTable::kInt,
                     TypeTable::kString,
                     TypeTable::kString};
  r2.bodyPredicates = {c, edge};
  loop(k, Opcode::ITER_SORTED, {c, 0, 0, 0}, [&] {
    emit(k, Opcode::LOAD, {0, 0, 0});
    emit(k, Opcode::LOAD, {0, 1, 1});
    emit(k, Opcode::MOVI, {2, std::uint32_t(-3)});
    loop(k, Opcode::ITER, {edge, 1, 0}, [&] {
      emit(k, Opcode::LOAD, {1, 0, 3});
      emit(k, Opcode::CALLF, {4, 0, 1, 0});
      emit(k, Opcode::NIL, {5});
      emit(k, Opcode::CONS, {5, 4, 5, listInt});
      emit(k, Opcode::STRUCT, {6, pair, 2, 0, 1});
      emit(k, Opcode::SEND, {d, 3, 2, 5, 6});
      emit(k, Opcode::EQ, {7, 0, 2, TypeTable::kInt});
      const std::size_t jf = emit(k, Opcode::JF, {7, 0});
      emit(k, Opcode::CALL, {8, 22, TypeTable::kInt, 1, 5});
      emit(k, Opcode::GLOBAL, {9, 0});
      emit(k, Opcode::ADDI, {8, 8, 9});
      emit(k, Opcode::MOVS, {10, 1});
      emit(k, Opcode::ARG, {11, 1});
      emit(k, Opcode::ACTION, {act, 3, 1, 8});
      k.code[jf + 2] = std::uint32_t(k.code.size());
      emit(k, Opcode::CFIRE, {1});
    });
  });
  emit(k, Opcode::RET);
  p->rules.push_back(std::move(r2));

  // d(L, S) -o d(L, S) as an in-place update, moving the fact to the back.
  Rule r3;
  CodeBlock& u = r3.block;
  u.label = "d(L, S) -o d(L, S)";
  u.slots = 1;
  u.registerTypes = {listInt, pair, TypeTable::kFloat, TypeTable::kInt};
  r3.bodyPredicates = {d};
  loop(u, Opcode::ITER, {d, 0, kLinConsume | kIterReturnOnFire}, [&] {
    emit(u, Opcode::LOAD, {0, 0, 0});
    emit(u, Opcode::LOAD, {0, 1, 1});
    emit(u, Opcode::FIELD, {2, 1, 1});
    emit(u, Opcode::MOVF, {2, lo(0.1), hi(0.1)});
    emit(u, Opcode::UPDATE, {0, kUpdateMoveToBack, 2, 0, 1});
    emit(u, Opcode::FIRE, {0});
  });
  emit(u, Opcode::RET);
  p->rules.push_back(std::move(r3));

  Process pr{c, {}};
  pr.block.label = "!c(X, Y) -> total(X)";
  pr.block.slots = 1;
  pr.block.registerTypes = {TypeTable::kInt};
  emit(pr.block, Opcode::LOAD, {0, 0, 0});
  emit(pr.block, Opcode::DERIVE, {total, 1, 0});
  emit(pr.block, Opcode::RET);
  p->processes.push_back(std::move(pr));

  CodeBlock ax;
  ax.registerTypes = {TypeTable::kInt, TypeTable::kFloat, TypeTable::kNode};
  emit(ax, Opcode::MOVI, {0, 5});
  emit(ax, Opcode::MOVF, {1, lo(2.5), hi(2.5)});
  emit(ax, Opcode::DERIVE, {c, 2, 0, 1});
  emit(ax, Opcode::MOVN, {2, 1});
  emit(ax, Opcode::DERIVE, {edge, 1, 2});
  // Two facts of c (int, float) and one of edge as data (version 4).
  emit(ax, Opcode::AXIOM_FACTS, {c, 6, std::uint32_t(-7), lo(-0.5), hi(-0.5), 2, lo(1e10), hi(1e10)});
  emit(ax, Opcode::AXIOM_FACTS, {edge, 1, 3});
  emit(ax, Opcode::RET);
  p->axiomBlocks.push_back(std::move(ax));
  p->nodeSourceIds = {0, 7, -3, std::int64_t(1) << 40};
  p->nodeAxioms = {0, Program::kNoAxioms, 0, Program::kNoAxioms};

  p->scheduling.order = PriorityOrder::Asc;
  p->scheduling.hasInitialPriority = true;
  p->scheduling.initialPriority = -1.5;
  p->scheduling.hasDefaultPriority = true;
  p->scheduling.defaultPriority = 1e-300;
  p->scheduling.staticNodes = true;
  p->indexes = {{c, 1}};
  p->highestArg = 1;
  // Where the axioms and rule 1 came from (version 3); each fact of AXIOM_FACTS from its first word.
  p->sourceFiles = {"full.meld", "lib/include.meld"};
  p->axiomBlocks[0].lines = {{0, 0, 3}, {7, 1, 12}, {19, 1, 13}, {25, 1, 14}, {28, 0, 15}};
  p->rules[1].block.lines = {{0, 0, 9}};
  return p;
}

// Word offset of the first instruction `op` of a block (decoding, so operands never match).
inline std::size_t findOp(const CodeBlock& b, Opcode op) {
  std::size_t at = 0;
  while (at < b.code.size() && b.code[at] != std::uint32_t(op)) {
    std::size_t len = 1;
    for (const char* l = opcodeInfo(Opcode(b.code[at])).operands; *l; ++l)
      len += *l == 'D' ? 2 : *l == '*' || *l == 'W' ? 1 + b.code[at + len] : 1;
    at += len;
  }
  return at;
}

// The message of the BytecodeError that verifyProgram raises, or "" if it accepts.
inline std::string verifyError(const Program& p) {
  try {
    verifyProgram(p);
  } catch (const BytecodeError& e) {
    return e.what();
  }
  return "";
}

}  // namespace bctest
