// How deep loops fetch the lists of the facts ahead (detail::listFetchDepth): ITER loops over a
// linear predicate with a list field whose body loads that field; the whole pipeline when the
// loaded list goes to a function, the first cell when it is only moved on; no others.
#define BOOST_TEST_MODULE vm_list_reading_loops
#include <boost/test/unit_test.hpp>

#include "bytecode_fixture.hpp"
#include "meldvm/bytecode_internal.hpp"

using namespace bctest;
using meldvm::detail::firstListField;
using meldvm::detail::kListFetchAhead;
using meldvm::detail::listFetchDepth;

namespace {

struct Preds {
  Program p;
  TypeId ints = p.types.list(TypeTable::kInt);
  PredId placed = pred(p, "placed", {TypeTable::kInt, ints}, true);  // linear, list in field 1
  PredId path = pred(p, "path", {ints}, false);                      // persistent
  PredId count = pred(p, "count", {TypeTable::kInt}, true);          // no list
};

// A block of one loop over `predicate` (ITER or ITER_KEY) into slot 0 whose body is `body`.
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

constexpr int kWhole = kListFetchAhead - 1, kFirstCell = 0, kNone = -1;

}  // namespace

BOOST_AUTO_TEST_CASE(first_list_field) {
  Preds t;
  BOOST_TEST(firstListField(t.p, t.placed) == 1);
  BOOST_TEST(firstListField(t.p, t.path) == 0);
  BOOST_TEST(firstListField(t.p, t.count) == -1);
}

BOOST_AUTO_TEST_CASE(a_list_handed_to_a_function_is_fetched_deep) {
  Preds t;
  const CodeBlock builtin = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    emit(b, Opcode::CALL, {2, 0, TypeTable::kBool, 2, 0, 1});  // r2 = builtin 0 (r0, r1)
    emit(b, Opcode::FIRE, {0});
  });
  BOOST_TEST(listFetchDepth(t.p, builtin.code, 0) == kWhole);
  // Inside an inner loop, to a user function: still the body of the outer loop.
  const CodeBlock nested = oneLoop(Opcode::ITER, t.placed, kLinConsume, [&](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    loop(b, Opcode::ITER, {t.count, 1, kIterLinear}, [&] { emit(b, Opcode::CALLF, {2, 0, 1, 1}); });
  });
  BOOST_TEST(listFetchDepth(t.p, nested.code, 0) == kWhole);
  BOOST_TEST(listFetchDepth(t.p, nested.code, 9) == kNone);  // the inner loop's predicate has no list
}

BOOST_AUTO_TEST_CASE(a_list_moved_on_is_fetched_at_its_first_cell) {
  Preds t;
  // Loaded and sent on (8queens' propagate rules), or handed to a function in another register.
  const CodeBlock moved = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    emit(b, Opcode::LOAD, {0, 0, 0});
    emit(b, Opcode::CALL, {2, 0, TypeTable::kBool, 1, 0});
    emit(b, Opcode::FIRE, {0});
  });
  BOOST_TEST(listFetchDepth(t.p, moved.code, 0) == kFirstCell);
}

BOOST_AUTO_TEST_CASE(other_loops_do_not_fetch) {
  Preds t;
  // The body reads another field only (a join on it, as belief propagation's in-msg(A, B, _)).
  const CodeBlock other = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 0, 0});
    emit(b, Opcode::FIRE, {0});
  });
  BOOST_TEST(listFetchDepth(t.p, other.code, 0) == kNone);
  // The list of another slot.
  const CodeBlock otherSlot = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {1, 1, 1});
  });
  BOOST_TEST(listFetchDepth(t.p, otherSlot.code, 0) == kNone);
  // A persistent predicate, and an index look-up.
  const CodeBlock persistent = oneLoop(Opcode::ITER, t.path, 0, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 0, 1});
  });
  BOOST_TEST(listFetchDepth(t.p, persistent.code, 0) == kNone);
  const CodeBlock keyed = oneLoop(Opcode::ITER_KEY, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
  });
  BOOST_TEST(listFetchDepth(t.p, keyed.code, 0) == kNone);
  // A load of the list after the loop's end is not in its body.
  CodeBlock after =
      oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) { emit(b, Opcode::FIRE, {0}); });
  after.code.pop_back();  // RET
  emit(after, Opcode::LOAD, {0, 1, 1});
  emit(after, Opcode::RET);
  BOOST_TEST(listFetchDepth(t.p, after.code, 0) == kNone);
}

BOOST_AUTO_TEST_CASE(lists_stay_put_unless_the_block_updates_a_fact) {
  Preds t;
  const CodeBlock walks = oneLoop(Opcode::ITER, t.placed, kLinConsume, [](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    emit(b, Opcode::CALL, {2, 0, TypeTable::kBool, 2, 0, 1});
    emit(b, Opcode::FIRE, {0});
  });
  BOOST_TEST(meldvm::detail::listsStayPut(walks.code));
  // An UPDATE anywhere in the block (here of another predicate's fact) may free a list a loop of
  // the block carries cells of: no carrying then.
  const CodeBlock updates = oneLoop(Opcode::ITER, t.placed, kLinConsume, [&](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    emit(b, Opcode::CALL, {2, 0, TypeTable::kBool, 2, 0, 1});
    loop(b, Opcode::ITER, {t.count, 1, kIterLinear}, [&] { emit(b, Opcode::UPDATE, {1, 0, 1, 0}); });
  });
  BOOST_TEST(!meldvm::detail::listsStayPut(updates.code));
}

BOOST_AUTO_TEST_CASE(written_register_is_the_computed_one) {
  Preds t;
  CodeBlock b;
  emit(b, Opcode::MOVF, {3, 0, 0});                          // fD: the D takes two words
  emit(b, Opcode::CALL, {2, 0, TypeTable::kBool, 2, 0, 1});  // r2 = builtin 0 (r0, r1)
  emit(b, Opcode::LOAD, {0, 1, 4});                          // r4 = field 1 of slot 0
  emit(b, Opcode::SEND, {t.count, 0, 1, 2});                 // writes none
  BOOST_TEST(meldvm::detail::writtenRegister(b.code, 0) == 3);
  BOOST_TEST(meldvm::detail::writtenRegister(b.code, 4) == 2);
  BOOST_TEST(meldvm::detail::writtenRegister(b.code, 11) == 4);
  BOOST_TEST(meldvm::detail::writtenRegister(b.code, 15) == -1);
}

// Two loops around a call that reads r1: the outer one loads r1 in its body, the inner one does
// not. So only the inner one keeps r1 (its runs see one value); r2, written by the call itself,
// is kept by no loop; r0, written before both, by the outer one.
BOOST_AUTO_TEST_CASE(the_outermost_loop_that_keeps_a_register) {
  Preds t;
  std::size_t callAt = 0, innerAt = 0;
  const CodeBlock nested = oneLoop(Opcode::ITER, t.placed, kLinConsume, [&](CodeBlock& b) {
    emit(b, Opcode::LOAD, {0, 1, 1});
    innerAt = b.code.size();
    loop(b, Opcode::ITER, {t.count, 1, kIterLinear}, [&] {
      callAt = b.code.size();
      emit(b, Opcode::CALL, {2, 0, TypeTable::kBool, 2, 0, 1});
    });
  });
  using meldvm::detail::outermostLoopKeeping;
  BOOST_TEST(outermostLoopKeeping(nested.code, callAt, 1) == std::int64_t(innerAt));
  BOOST_TEST(outermostLoopKeeping(nested.code, callAt, 0) == 0);
  BOOST_TEST(outermostLoopKeeping(nested.code, callAt, 2) == -1);
  // An instruction after the loops' end is in none of them.
  BOOST_TEST(outermostLoopKeeping(nested.code, nested.code.size() - 1, 0) == -1);
}
