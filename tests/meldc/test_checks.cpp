#define BOOST_TEST_MODULE meldc_checks
#include <boost/test/unit_test.hpp>

#include "meldc/bindings.hpp"
#include "meldc/homes.hpp"
#include "meldc/types.hpp"
#include "test_support.hpp"

using namespace meldc;

// Parses, resolves names and runs the semantic checks in the order of the driver.
struct Checked : Parsed {
  explicit Checked(const std::string& text) : Parsed(text, true) {
    if (!ok()) return;
    checkBindings(*program, diag);
    checkHomes(*program, diag);
    checkTypes(*program, diag);
  }
  bool has(const std::string& message) const { return errors().find(message) != std::string::npos; }
};

BOOST_AUTO_TEST_CASE(int_literals_adapt_to_float) {
  Checked p(
      "type linear h(node, float).\ntype linear l(node, list float).\nconst c = 2.\n"
      "h(@1, 3).\nl(@1, [1.5, 2, 3]).\nh(A, X) -o h(A, X + 1), h(A, float(c) * 2).\n");
  BOOST_TEST(p.ok(), p.errors());
}

BOOST_AUTO_TEST_CASE(int_variables_do_not_become_float) {
  Checked p("type linear i(node, int).\ntype linear h(node, float).\ni(A, N) -o h(A, N).\n");
  BOOST_TEST(p.has("t.meld:3:17: error: type mismatch: variable 'N' has type 'int' but argument 2 of 'h' "
                   "expects 'float'"),
             p.errors());
  BOOST_TEST(p.diag.errorCount() == 1);
}

BOOST_AUTO_TEST_CASE(float_literal_into_int_field) {
  Checked p("type linear i(node, int).\ni(@1, 2.5).\n");
  BOOST_TEST(p.has("expression has type 'float' but argument 2 of 'i' expects 'int'"), p.errors());
}

BOOST_AUTO_TEST_CASE(one_type_per_variable) {
  Checked p("type linear s(node, string).\ntype linear i(node, int).\ns(A, X), i(A, X) -o 1.\n");
  BOOST_TEST(p.has("variable 'X' has type 'string' but argument 2 of 'i' expects 'int'"), p.errors());
}

BOOST_AUTO_TEST_CASE(builtin_signatures_and_polymorphism) {
  Checked good(
      "type linear l(node, list int).\ntype linear i(node, int).\n"
      "l(A, L) -o i(A, lnth(L, 0) + llength(lreverse(L))), l(A, lremove(L, 3)).\n");
  BOOST_TEST(good.ok(), good.errors());
  Checked bad("type linear l(node, list int).\ntype linear s(node, string).\nl(A, L) -o s(A, lnth(L, 0)).\n");
  BOOST_TEST(bad.has("expression has type 'int' but argument 2 of 's' expects 'string'"), bad.errors());
  Checked arg("type linear i(node, int).\ni(A, N) -o i(A, str2int(N)).\n");
  BOOST_TEST(arg.has("argument 1 of function 'str2int' expects 'string'"), arg.errors());
}

BOOST_AUTO_TEST_CASE(conditions_are_bool) {
  Checked p("type linear i(node, int).\ni(A, N), llength([N]) -o 1.\n");
  BOOST_TEST(p.has("a condition must be a bool, but 'llength' returns 'int'"), p.errors());
}

BOOST_AUTO_TEST_CASE(aggregate_variables_change_type_in_the_head) {
  Checked p(
      "type linear b(node, int).\ntype linear c(node, list int).\ntype linear go(node).\n"
      "go(A) -o [collect => L | b(A, L) | c(A, L)].\n");
  BOOST_TEST(p.ok(), p.errors());
}

BOOST_AUTO_TEST_CASE(head_variables_must_be_bound) {
  Checked p(
      "type linear i(node, int).\ni(A, N) -o i(A, M).\ni(A, N), Q > 1 -o 1.\ni(A, N) -o X = N + 1, i(A, "
      "X).\n");
  BOOST_TEST(p.has("t.meld:2:17: error: variable 'M' is not bound by the body"), p.errors());
  BOOST_TEST(p.has("t.meld:3:10: error: variable 'Q' is not bound by the body"), p.errors());
  BOOST_TEST(p.diag.errorCount() == 2);
}

BOOST_AUTO_TEST_CASE(variable_axioms_bind_their_home) {
  Checked p("type linear d(node, int).\nd(A, 99).\nd(@1, N).\n");
  BOOST_TEST(p.has("t.meld:3:7: error: variable 'N' is not bound"), p.errors());
  BOOST_TEST(p.diag.errorCount() == 1);
}

BOOST_AUTO_TEST_CASE(comprehension_variables_listed_exactly) {
  Checked good("type route e(node, node).\ntype linear v(node).\nv(A) -o {B | !e(A, B) | v(B)}.\n");
  BOOST_TEST(good.ok(), good.errors());
  Checked bad("type route e(node, node).\ntype linear v(node).\nv(A) -o {B, C | !e(A, B) | v(B)}.\n");
  BOOST_TEST(bad.has("variable 'C' is listed but not bound inside the comprehension"), bad.errors());
}

BOOST_AUTO_TEST_CASE(body_facts_at_host_or_route_neighbour) {
  Checked good("type route e(node, node).\ntype linear v(node).\nv(A), !e(A, B), v(B) -o v(A).\n");
  BOOST_TEST(good.ok(), good.errors());
  Checked bad("type linear v(node).\nv(A), v(B) -o v(A).\n");
  BOOST_TEST(bad.has("t.meld:2:9: error: bad home argument: 'v' is at 'B'"), bad.errors());
}

BOOST_AUTO_TEST_CASE(home_argument_types) {
  Checked p("type linear v(node, int).\ntype linear w(thread, int).\nv(3, 1).\nv(A, N) -o w(A, N).\n");
  BOOST_TEST(p.has("the home argument of 'v' expects 'node'"), p.errors());
  BOOST_TEST(p.has("variable 'A' has type 'node' but the home argument of 'w' expects 'thread'"), p.errors());
}

BOOST_AUTO_TEST_CASE(function_calls_in_bodies_do_not_bind) {
  Checked p("type linear i(node, int).\ni(A, N), queens_violation(Y, [1]) -o 1.\n");
  BOOST_TEST(p.has("t.meld:2:27: error: variable 'Y' is not bound by the body"), p.errors());
}

BOOST_AUTO_TEST_CASE(fact_assignments_in_any_order) {
  Checked p("type linear a(node, int).\na(@1, X), X = 3.\nX = Y + 1, Y = 2, a(@1, X).\na(@1, Z), Z = Q.\n");
  BOOST_TEST(p.has("t.meld:4:7: error: variable 'Z' is not bound"), p.errors());
  BOOST_TEST(p.has("t.meld:4:15: error: variable 'Q' is not bound"), p.errors());
  BOOST_TEST(p.diag.errorCount() == 2);
}
