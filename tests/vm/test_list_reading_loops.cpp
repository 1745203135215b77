// Which loops fetch the lists of the facts ahead (detail::loopReadsLists): ITER loops over a
// linear predicate with a list field whose body reads that field, and no others.
#define BOOST_TEST_MODULE vm_list_reading_loops
#include <boost/test/unit_test.hpp>

#include "bytecode_fixture.hpp"
#include "meldvm/bytecode_internal.hpp"

using namespace bctest;
using meldvm::detail::firstListField;
using meldvm::detail::loopReadsLists;

namespace {

struct Preds {
  Program p;
  TypeId ints = p.types.list(TypeTable::kInt);
  PredId placed = pred(p, "placed", {TypeTable::kInt, ints}, true);  // linear, list in field 1
  PredId path = pred(p, "path", {ints}, false);                      // persistent
  PredId count = pred(p, "count", {TypeTable::kInt}, true);          // no list
};

// A block of one loop over `predicate` (ITER or ITER_KEY) into slot 0 whose body is `body`;
// returns the loop's offset (0) and the block.
CodeBlock oneLoop(Opcode iter, PredId predicate, std::uint32_t flags,
                  const std::function<void(CodeBlock&)>& body) {
  CodeBlock b;
  b.slots = 2;
  b.registerTypes = {TypeTable::kInt, TypeTable::kInt, TypeTable::kBool};
  if (iter == Opcode::ITER_KEY)
    loop(b, iter, {predicate, 0, flags, 0, 1}, [&] { body(b); });
  else
    loop(b, iter, {predicate, 0, flags}, [&] { body(b); });
  emit(b, Opcode::RET);
  return b;
}

}  // namespace

BOOST_AUTO_TEST_CASE(first_list_field) {
  Preds t;
  BOOST_TEST(firstListField(t.p, t.placed) == 1);
  BOOST_TEST(firstListField(t.p, t.path) == 0);
  BOOST_TEST(firstListField(t.p, t.count) == -1);
}

BOOST_AUTO_TEST_CASE(a_linear_loop_that_loads_its_list_reads_lists) {
  Preds t;
  const CodeBlock direct = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    emit(b, Opcode::FIRE, {0});
  });
  BOOST_TEST(loopReadsLists(t.p, direct.code, 0));
  // Behind a test and inside an inner loop: still the body of the outer loop.
  const CodeBlock nested = oneLoop(Opcode::ITER, t.placed, kLinConsume, [&](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 0, 0});
    loop(b, Opcode::ITER, {t.count, 1, kIterLinear}, [&] { emit(b, Opcode::LOAD, {0, 1, 1}); });
  });
  BOOST_TEST(loopReadsLists(t.p, nested.code, 0));
  BOOST_TEST(!loopReadsLists(t.p, nested.code, 9));  // the inner loop's predicate has no list
}

BOOST_AUTO_TEST_CASE(other_loops_do_not) {
  Preds t;
  // The body reads another field only (a join on it, as belief propagation's in-msg(A, B, _)).
  const CodeBlock other = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 0, 0});
    emit(b, Opcode::FIRE, {0});
  });
  BOOST_TEST(!loopReadsLists(t.p, other.code, 0));
  // The list of another slot.
  const CodeBlock otherSlot = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {1, 1, 1});
  });
  BOOST_TEST(!loopReadsLists(t.p, otherSlot.code, 0));
  // A persistent predicate, and an index look-up.
  const CodeBlock persistent = oneLoop(Opcode::ITER, t.path, 0, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 0, 1});
  });
  BOOST_TEST(!loopReadsLists(t.p, persistent.code, 0));
  const CodeBlock keyed = oneLoop(Opcode::ITER_KEY, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
  });
  BOOST_TEST(!loopReadsLists(t.p, keyed.code, 0));
  // A load of the list after the loop's end is not in its body.
  CodeBlock after =
      oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) { emit(b, Opcode::FIRE, {0}); });
  after.code.pop_back();  // RET
  emit(after, Opcode::LOAD, {0, 1, 1});
  emit(after, Opcode::RET);
  BOOST_TEST(!loopReadsLists(t.p, after.code, 0));
}
