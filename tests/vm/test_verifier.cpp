// verifyProgram: each kind of malformed code block is refused with a message that names the block,
// the word offset, the opcode and the problem.
#define BOOST_TEST_MODULE vm_verifier
#include <boost/test/unit_test.hpp>

#include "bytecode_fixture.hpp"
#include "meldvm/builtins.hpp"

using namespace bctest;

namespace {

const std::string kRule1 = "rule 1 (a(A, N) -o b(A, N+1)): ";

// smallProgram with rule 1's code changed by `edit`; returns the verifier's message.
template <class Edit>
std::string rule1Error(Edit edit) {
  auto p = smallProgram();
  edit(*p, p->rules[1].block);
  return verifyError(*p);
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

BOOST_AUTO_TEST_CASE(valid_programs_pass) {
  BOOST_TEST(verifyError(*smallProgram()) == "");
  BOOST_TEST(verifyError(*fullProgram()) == "");
}

BOOST_AUTO_TEST_CASE(register_type_mismatch) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.registerTypes[3] = TypeTable::kFloat; });
  BOOST_TEST(e == kRule1 + "word 16: ADDI: register 3 has type float, expected int");
}

BOOST_AUTO_TEST_CASE(register_out_of_range) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[14] = 9; });  // MOVI r9
  BOOST_TEST(e == kRule1 + "word 13: MOVI: register 9 out of range (the block has 4 registers)");
}

BOOST_AUTO_TEST_CASE(jump_into_an_instruction) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[4] = 26; });  // ITER exit mid-FIRE
  BOOST_TEST(e == kRule1 + "word 0: ITER: jump target 26 is not an instruction boundary");
}

BOOST_AUTO_TEST_CASE(jump_out_of_the_block) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[4] = 100; });
  BOOST_TEST(has(e, "word 0: ITER: jump target 100 is outside the block (29 words)"), e);
}

BOOST_AUTO_TEST_CASE(jump_out_of_a_loop) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) {
    b.registerTypes.push_back(TypeTable::kBool);
    // JF r4 to the RET after the loop (word 31 once the MOVI moved down), skipping the NEXT.
    b.code[13] = std::uint32_t(Opcode::JF);
    b.code[14] = 4;
    b.code[15] = 31;
    b.code.insert(b.code.begin() + 16, {std::uint32_t(Opcode::MOVI), 2, 1});
    b.code[4] = 31;
  });
  BOOST_TEST(has(e, "word 13: JF: jump to word 31 leaves or enters a loop body"), e);
}

BOOST_AUTO_TEST_CASE(unclosed_loop) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) {
    b.code.erase(b.code.begin() + 27);  // the NEXT
    b.code[4] = 27;
  });
  BOOST_TEST(e == kRule1 + "word 0: ITER: loop never closed by a NEXT (exit word 27)");
}

BOOST_AUTO_TEST_CASE(loops_must_nest) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[4] = 27; });  // exit at the NEXT
  BOOST_TEST(has(e, "word 27: NEXT: closes the loop of word 0 whose exit is word 27"), e);
}

BOOST_AUTO_TEST_CASE(next_outside_a_loop) {
  auto p = smallProgram();
  p->globalsInit.code = {std::uint32_t(Opcode::NEXT), std::uint32_t(Opcode::RET)};
  BOOST_TEST(verifyError(*p) == "globals: word 0: NEXT: NEXT outside a loop");
}

BOOST_AUTO_TEST_CASE(fire_outside_a_loop) {
  auto p = smallProgram();
  CodeBlock& b = p->rules[1].block;
  b.code = {std::uint32_t(Opcode::FIRE), 0, std::uint32_t(Opcode::RET)};
  BOOST_TEST(verifyError(*p) == kRule1 + "word 0: FIRE: outside a loop");
}

BOOST_AUTO_TEST_CASE(missing_ret) {
  const std::string e =
      rule1Error([](Program&, CodeBlock& b) { b.code.back() = std::uint32_t(Opcode::NEXT); });
  BOOST_TEST(e == kRule1 + "does not end with RET");
}

BOOST_AUTO_TEST_CASE(wrong_derive_arity) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) {
    b.code.erase(b.code.begin() + 24);  // drop r3
    b.code[22] = 1;
    b.code[4] = 27;
  });
  BOOST_TEST(e == kRule1 + "word 20: DERIVE: 1 registers for b/2 of 2 arguments");
}

BOOST_AUTO_TEST_CASE(wrong_derive_field_type) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[24] = 0; });  // b(A, A)
  BOOST_TEST(e == kRule1 + "word 20: DERIVE: register 0 has type node, expected int (argument 1 of b/2)");
}

BOOST_AUTO_TEST_CASE(unknown_opcode) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[13] = 9999; });
  BOOST_TEST(e == kRule1 + "word 13: unknown opcode 9999");
}

BOOST_AUTO_TEST_CASE(count_past_the_end) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[22] = 0xffffffff; });
  BOOST_TEST(e == kRule1 + "word 20: register count 4294967295 runs past the end of the block");
}

BOOST_AUTO_TEST_CASE(unknown_predicate) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[21] = 77; });  // DERIVE p=77
  BOOST_TEST(e == kRule1 + "word 20: DERIVE: unknown predicate 77");
}

BOOST_AUTO_TEST_CASE(bad_slot) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) { b.code[6] = 5; });  // LOAD s=5
  BOOST_TEST(e == kRule1 + "word 5: LOAD: slot 5 out of range (the block has 1 slots)");
}

BOOST_AUTO_TEST_CASE(load_of_an_unbound_slot) {
  const std::string e = rule1Error([](Program&, CodeBlock& b) {
    b.slots = 2;
    b.code[6] = 1;
  });
  BOOST_TEST(e == kRule1 + "word 5: LOAD: slot 1 is not bound here (no enclosing loop binds it)");
}

BOOST_AUTO_TEST_CASE(load_field_type) {
  const std::string e =
      rule1Error([](Program&, CodeBlock& b) { b.code[7] = 1; });  // LOAD f=1 into the node register
  BOOST_TEST(e == kRule1 + "word 5: LOAD: register 0 has type node, expected int (field 1 of a/2)");
}

BOOST_AUTO_TEST_CASE(iter_flags_and_rebinding) {
  BOOST_TEST(has(rule1Error([](Program&, CodeBlock& b) { b.code[3] = 64; }), "ITER: unknown flag bits 64"));
  auto p = fullProgram();
  p->rules[2].block.code[findOp(p->rules[2].block, Opcode::ITER) + 2] = 0;  // the inner ITER rebinds slot 0
  const std::string e = verifyError(*p);
  BOOST_TEST(has(e, "ITER: slot 0 is already bound by an enclosing loop"), e);
}

BOOST_AUTO_TEST_CASE(process_slot_zero_is_bound) {
  auto p = fullProgram();
  BOOST_TEST(verifyError(*p) == "");
  p->processes[0].block.slots = 0;
  BOOST_TEST(has(verifyError(*p), "process 0 on c (!c(X, Y) -> total(X)): "), verifyError(*p));
  // Outside process blocks slot 0 needs a loop.
  auto q = fullProgram();
  q->axiomBlocks[0].slots = 1;
  q->axiomBlocks[0].code.insert(q->axiomBlocks[0].code.begin(), {std::uint32_t(Opcode::LOAD), 0, 0, 0});
  BOOST_TEST(verifyError(*q) ==
             "axioms 0: word 0: LOAD: slot 0 is not bound here (no enclosing loop binds it)");
}

BOOST_AUTO_TEST_CASE(update_arity) {
  auto p = fullProgram();
  CodeBlock& u = p->rules[3].block;
  // ITER 0-4, LOAD 5, LOAD 9, FIELD 13, MOVF 17, UPDATE 21-26 (S X count r0 r1).
  BOOST_REQUIRE(u.code[21] == std::uint32_t(Opcode::UPDATE));
  u.code[26] = 0;  // UPDATE d(L, L)
  BOOST_TEST(verifyError(*p) ==
             "rule 3 (d(L, S) -o d(L, S)): word 21: UPDATE: register 0 has type list int, expected "
             ":(int, float) (argument 1 of d/2)");
}

BOOST_AUTO_TEST_CASE(struct_and_call_counts) {
  auto p = fullProgram();
  std::vector<std::uint32_t>& k = p->rules[2].block.code;
  const std::size_t st = findOp(p->rules[2].block, Opcode::STRUCT);
  k[st + 3] = 1;  // STRUCT with one register: the second becomes an opcode
  k[st + 5] = std::uint32_t(Opcode::NEXT);
  std::string e = verifyError(*p);
  BOOST_TEST(has(e, "STRUCT: 1 registers for :(int, float) of 2 arguments"), e);

  auto q = fullProgram();
  std::vector<std::uint32_t>& c = q->rules[2].block.code;
  const std::size_t cf = findOp(q->rules[2].block, Opcode::CALLF);
  c[cf + 4] = 1;  // inc(X) with the float register
  e = verifyError(*q);
  BOOST_TEST(has(e, "CALLF: register 1 has type float, expected int (argument 0 of function inc)"), e);
}

BOOST_AUTO_TEST_CASE(placement_rules) {
  auto p = smallProgram();
  p->globalsInit.code = {std::uint32_t(Opcode::AXIOMS), std::uint32_t(Opcode::RET)};
  BOOST_TEST(verifyError(*p) == "globals: word 0: AXIOMS: outside rule 0");
  auto q = fullProgram();
  q->functions[0].block.code.insert(q->functions[0].block.code.begin(),
                                    {std::uint32_t(Opcode::SETGLOBAL), 0, 0});
  BOOST_TEST(verifyError(*q) == "function 0 (inc): word 0: SETGLOBAL: outside the globals initialiser");
  auto f = fullProgram();
  f->functions[0].block.registerTypes[1] = TypeTable::kFloat;
  BOOST_TEST(verifyError(*f) == "function 0 (inc): register 1 does not have the result type");
}

// AXIOM_FACTS: whole facts of a predicate of int, float, bool and node fields, valid bools and
// nodes, in axiom blocks only (the interpreter decodes the words without a check).
BOOST_AUTO_TEST_CASE(axiom_facts_data) {
  const auto withFacts = [](std::vector<std::uint32_t> instr) {
    auto p = fullProgram();
    std::vector<std::uint32_t>& code = p->axiomBlocks[0].code;
    code.insert(code.begin(), instr.begin(), instr.end());
    return verifyError(*p);
  };
  const PredId c = fullProgram()->predicates.find("c"), edge = fullProgram()->predicates.find("edge");
  const PredId d = fullProgram()->predicates.find("d"), act = fullProgram()->predicates.find("act");
  const auto op = std::uint32_t(Opcode::AXIOM_FACTS);
  BOOST_TEST(withFacts({op, edge, 2, 0, 3}) == "");
  BOOST_TEST(withFacts({op, c, 0}) == "");      // no fact at all
  std::string e = withFacts({op, c, 2, 1, 0});  // c takes 3 words a fact
  BOOST_TEST(e == "axioms 0: word 0: AXIOM_FACTS: 2 data words for facts of 3 words each", e);
  e = withFacts({op, edge, 2, 3, 4});
  BOOST_TEST(e == "axioms 0: word 0: AXIOM_FACTS: node @4 at word 4 is not one of the program's 4 nodes", e);
  e = withFacts({op, d, 1, 0});
  BOOST_TEST(has(e, "d/2 has a field that is not an int, float, bool or node"), e);
  e = withFacts({op, act, 1, 0});
  BOOST_TEST(has(e, "act/1 is a thread or action predicate"), e);
  e = withFacts({op, edge, 1000, 0});  // the count runs past the block
  BOOST_TEST(has(e, "data word count 1000 runs past the end of the block"), e);
  // A bool field takes 0 or 1 only.
  for (const std::uint32_t value : {1u, 2u}) {
    auto b = fullProgram();
    const PredId flag = pred(*b, "flag", {TypeTable::kBool}, false);
    b->axiomBlocks[0].code.insert(b->axiomBlocks[0].code.begin(), {op, flag, 1, value});
    e = verifyError(*b);
    BOOST_TEST(e == (value == 1 ? "" : "axioms 0: word 0: AXIOM_FACTS: bool 2 at word 3 is not 0 or 1"), e);
  }
  // Outside axiom blocks.
  auto q = fullProgram();
  q->globalsInit.code.insert(q->globalsInit.code.begin(), {op, edge, 1, 0});
  e = verifyError(*q);
  BOOST_TEST(e == "globals: word 0: AXIOM_FACTS: outside an axiom block", e);
}

BOOST_AUTO_TEST_CASE(unknown_builtin) {
  auto p = fullProgram();
  std::vector<std::uint32_t>& k = p->rules[2].block.code;
  const std::size_t call = findOp(p->rules[2].block, Opcode::CALL);
  k[call + 2] = meldvm::kBuiltinIdCount;  // the first id past the table (user externs go by EXTERN)
  BOOST_TEST(has(verifyError(*p), "CALL: unknown built-in " + std::to_string(meldvm::kBuiltinIdCount)),
             verifyError(*p));
}

BOOST_AUTO_TEST_CASE(table_references) {
  auto p = smallProgram();
  p->initPredicate = 9;
  BOOST_TEST(verifyError(*p) == "init predicate 9 is not a predicate");
  p = smallProgram();
  p->rules[1].bodyPredicates = {12};
  BOOST_TEST(verifyError(*p) == "rule 1 (a(A, N) -o b(A, N+1)): unknown body predicate 12");
  p = smallProgram();
  p->nodeAxioms = {3};
  BOOST_TEST(verifyError(*p) == "node 0: unknown axiom block 3");
  p = smallProgram();
  p->nodeAxioms.clear();
  BOOST_TEST(verifyError(*p) == "0 axiom entries for 1 nodes");
  p = smallProgram();
  p->indexes = {{1, 2}};
  BOOST_TEST(verifyError(*p) == "index on field 2 of a, which has 2 fields");
  p = smallProgram();
  p->rules[1].block.registerTypes[0] = 40;
  BOOST_TEST(verifyError(*p) == kRule1 + "register 0 has unknown type 40");
}
