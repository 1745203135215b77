#define BOOST_TEST_MODULE meldc_names
#include <boost/test/unit_test.hpp>

#include "test_support.hpp"

using namespace meldc;

static bool hasMessage(const Parsed& p, const std::string& text) {
  return p.errors().find(text) != std::string::npos;
}

BOOST_AUTO_TEST_CASE(valid_program_resolves) {
  Parsed p(
      "type route edge(node, node).\n"
      "type linear visit(node).\n"
      "type linear visited(node).\n"
      "const limit = 3.\n"
      "fun inc(int X) : int = X + 1.\n"
      "visit(A), N = inc(limit), N > 0 -o {B | !edge(A, B) | visit(B)}, visited(A), !setColor2(A, 1).\n",
      true);
  BOOST_TEST(p.ok(), p.errors());
  BOOST_TEST(p.diag.warningCount() == 0, p.errors());
}

BOOST_AUTO_TEST_CASE(names_are_case_insensitive) {
  Parsed p("type linear viSit(node).\nvisit(A) -o vISIT(A).\n", true);
  BOOST_TEST(p.ok(), p.errors());
  Parsed dup("type a(node).\ntype aB(node).\ntype linear ab(node).\n", true);
  BOOST_TEST(hasMessage(dup, "predicate 'ab' is declared more than once"), dup.errors());
  BOOST_TEST(hasMessage(dup, "t.meld:2:6: note: previous declaration is here"), dup.errors());
}

BOOST_AUTO_TEST_CASE(unknown_predicate_with_suggestion) {
  Parsed p("type linear visit(node).\nvisit(A) -o visits(A).\n", true);
  BOOST_TEST(hasMessage(p, "t.meld:2:13: error: unknown predicate 'visits'; did you mean 'visit'?"),
             p.errors());
}

BOOST_AUTO_TEST_CASE(arity_mismatch) {
  Parsed p("type linear a(node, int).\na(A) -o a(A, 1, 2).\n", true);
  BOOST_TEST(hasMessage(p, "t.meld:2:1: error: predicate 'a' takes 2 arguments, 1 given"), p.errors());
  BOOST_TEST(hasMessage(p, "t.meld:2:9: error: predicate 'a' takes 2 arguments, 3 given"), p.errors());
  BOOST_TEST(p.diag.errorCount() == 2);
}

BOOST_AUTO_TEST_CASE(marks_must_fit_the_predicate) {
  Parsed p(
      "type linear l(node).\ntype e(node).\n"
      "!l(A) -o e(A).\n"  // ! on linear: error; e in head without !: warning
      "?e(A) -o 1.\n"     // ? on persistent
      "$e(A) -o 1.\n"     // $ on persistent
      "l(A) -o $l(A).\n"  // $ in head
      "e(A) -o 1.\n",     // persistent without !: warning
      true);
  BOOST_TEST(hasMessage(p, "'l' is linear; '!' is only for persistent predicates"), p.errors());
  BOOST_TEST(hasMessage(p, "'e' is persistent; '?' is only for linear predicates"), p.errors());
  BOOST_TEST(hasMessage(p, "'e' is persistent; '$' is only for linear predicates"), p.errors());
  BOOST_TEST(hasMessage(p, "'$' is not allowed in a head"), p.errors());
  BOOST_TEST(p.diag.errorCount() == 4);
  BOOST_TEST(p.diag.warningCount() == 2);
}

BOOST_AUTO_TEST_CASE(functions_constants_and_types) {
  Parsed p(
      "type linear a(node, number).\n"
      "fun f(int X) : int = Y.\n"
      "a(A, N) -o a(A, g(N)), a(A, lnth(N)), a(A, n-1).\n",
      true);
  BOOST_TEST(hasMessage(p, "unknown type 'number'"), p.errors());
  BOOST_TEST(hasMessage(p, "unknown variable 'Y'"), p.errors());
  BOOST_TEST(hasMessage(p, "unknown function 'g'"), p.errors());
  BOOST_TEST(hasMessage(p, "function 'lnth' takes 2 arguments, 1 given"), p.errors());
  BOOST_TEST(hasMessage(p, "unknown constant 'n-1'; '-' is part of names, write 'n - 1' to subtract"),
             p.errors());
}

BOOST_AUTO_TEST_CASE(boolean_calls_in_bodies) {
  Parsed p("type linear q(node, int, list int).\nq(A, Y, L), queens_violation(Y, L) -o 1.\n", true);
  BOOST_TEST(p.ok(), p.errors());
}

BOOST_AUTO_TEST_CASE(instructions_only_in_heads) {
  Parsed p("type linear a(node).\na(A), set-priority(A, 1.0) -o 1.\nschedule-next(@1).\n", true);
  BOOST_TEST(hasMessage(p, "'set-priority' is an instruction; it can only be used in a head"), p.errors());
  BOOST_TEST(hasMessage(p, "'schedule-next' cannot be used in a fact"), p.errors());
}

BOOST_AUTO_TEST_CASE(declaration_checks) {
  Parsed p(
      "type a(int).\n"
      "type b(node, min int, max int).\n"
      "type c(node, min string).\n"
      "type linear d(node).\n"
      "index d/3.\n"
      "compact zz.\n",
      true);
  BOOST_TEST(hasMessage(p, "the first argument of 'a' is its home"), p.errors());
  BOOST_TEST(hasMessage(p, "'b' has more than one aggregate field"), p.errors());
  BOOST_TEST(hasMessage(p, "min aggregates int or float fields, not 'string'"), p.errors());
  BOOST_TEST(hasMessage(p, "index field 3 does not exist"), p.errors());
  BOOST_TEST(hasMessage(p, "unknown predicate 'zz' in compact directive"), p.errors());
}

BOOST_AUTO_TEST_CASE(node_subtype_and_alias_homes) {
  Parsed p("node page.\ntype page host2.\ntype linear r(host2, int).\ntype linear s(page).\n", true);
  BOOST_TEST(p.ok(), p.errors());
}
