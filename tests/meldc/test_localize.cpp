#define BOOST_TEST_MODULE meldc_localize
#include <boost/test/unit_test.hpp>
#include <sstream>
#include <string>

#include "meldc/ast_dump.hpp"
#include "meldc/frontend.hpp"
#include "meldc/ground_facts.hpp"
#include "meldc/localize.hpp"
#include "temp_dir.hpp"

using namespace meldc;

namespace {

// Runs the whole front end (localization included) on one file.
struct Compiled : TempDir {
  SourceManager sources;
  std::ostringstream messages;
  Diagnostics diag{sources, messages};
  std::optional<ast::Program> program;

  explicit Compiled(const std::string& text) {
    program = runFrontEnd(FrontEndInput{write("main.meld", text), {}, {}}, sources, diag);
    // Literal facts come out compact (ground_fact.hpp): as statements again, the tests read every
    // fact in `rules`.
    if (program) materializeGroundFacts(*program, sources);
  }
  bool ok() const { return program.has_value() && !diag.hasErrors(); }
  std::string errors() const { return messages.str(); }

  // "body -o head" of rule i, "(generated)" appended for generated rules.
  std::string rule(size_t i) const {
    const ast::Rule& r = program->rules.at(i);
    auto join = [](const std::vector<ast::Term>& ts) {
      std::string out;
      for (size_t k = 0; k < ts.size(); ++k) out += (k ? ", " : "") + toString(ts[k]);
      return out;
    };
    std::string s = join(r.body) + (r.kind == ast::RuleKind::Datalog ? " :- " : " -o ") + join(r.head);
    return r.generated ? s + " (generated)" : s;
  }
  // "[linear ][route ][reverse-route ]name(types)[ generated]" of predicate i.
  std::string pred(size_t i) const {
    const ast::PredicateDecl& d = program->predicates.at(i);
    std::string s = std::string(d.linear ? "linear " : "") + (d.route ? "route " : "") +
                    (d.reverseRoute ? "reverse-route " : "") + d.name + "(";
    for (size_t k = 0; k < d.fields.size(); ++k) s += (k ? ", " : "") + toString(d.fields[k].type);
    return s + ")" + (d.generated ? " generated" : "");
  }
  size_t rules() const { return program->rules.size(); }
  size_t preds() const { return program->predicates.size(); }
  std::string dump() const {
    std::ostringstream out;
    dumpProgram(*program, sources, out);
    return out.str();
  }
};

const char* kNeighbor =
    "type route neighbor(node, node).\n"
    "type ending(node).\n"
    "type middle(node).\n"
    "type nearEnding(node).\n";

}  // namespace

// §6.7: the host part is only the route subgoal, so the rule moves to the neighbour.
BOOST_AUTO_TEST_CASE(rule_with_only_the_route_at_the_host_moves_to_the_neighbour) {
  Compiled c(
      "type route neighbor(node, node, int).\n"
      "type neighborCount(node, int).\n"
      "type dist(node, min int).\n"
      "!neighborCount(X, 1) -o !dist(X, 0).\n"
      "!neighbor(X, Y, _), !dist(Y, N) -o !dist(X, N + 1).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_TEST(c.preds() == 4u);
  BOOST_TEST(c.pred(3) == "route reverse-route ___robhgien(node, node, int) generated");
  BOOST_REQUIRE(c.rules() == 3u);
  BOOST_TEST(c.rule(0) == "!neighbor(X0, X1, X2) -o !___robhgien(X1, X0, X2) (generated)");
  BOOST_TEST(c.rule(1) == "!neighborCount(X, 1) -o !dist(X, 0)");
  BOOST_TEST(c.rule(2) == "!___robhgien(Y, X, _), !dist(Y, N) -o !dist(X, (N + 1))");
  BOOST_TEST(c.program->rules.at(0).loc.line == 5u);  // generated items point at their rule
}

// The ends-near example of §6.7: helper, its rule, the rewritten rule; helper persistent.
BOOST_AUTO_TEST_CASE(ends_near_creates_a_persistent_helper) {
  Compiled c(std::string(kNeighbor) +
             "!neighbor(@1, @2). !neighbor(@2, @1). !ending(@2). !middle(@1).\n"
             "!neighbor(A, B), !ending(B), !middle(A) -o !nearEnding(A), !setColor2(A, 3).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.preds() == 6u);
  BOOST_TEST(c.pred(3) == "nearEnding(node)");
  BOOST_TEST(c.pred(4) == "__mangledname1(node) generated");  // helpers first, then inverses
  BOOST_TEST(c.pred(5) == "route reverse-route ___robhgien(node, node) generated");
  BOOST_REQUIRE(c.rules() == 7u);
  BOOST_TEST(c.rule(0) == "!neighbor(X0, X1) -o !___robhgien(X1, X0) (generated)");
  BOOST_TEST(c.rule(1) == "!___robhgien(B, A), !ending(B) -o !__mangledname1(A) (generated)");
  BOOST_TEST(c.rule(2) == " -o !neighbor(@1, @0)");  // the facts keep their order (renumbered)
  BOOST_TEST(c.rule(6) == "!__mangledname1(A), !middle(A) -o !nearEnding(A), !setColor2(A, 3)");
  BOOST_TEST(c.program->rules.at(6).loc.line == 6u);
}

// A linear neighbour subgoal makes the helper linear (rule and subgoals without `!`); a linear
// route gets a linear inverse rule.
BOOST_AUTO_TEST_CASE(linear_neighbour_subgoal_makes_the_helper_linear) {
  Compiled c(
      "type linear route link(node, node).\n"
      "type linear token(node, int).\n"
      "type middle(node).\n"
      "type got(node, int).\n"
      "link(A, B), token(B, N), !middle(A) -o !got(A, N).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.preds() == 6u);
  BOOST_TEST(c.pred(4) == "linear __mangledname1(node, int) generated");
  BOOST_TEST(c.pred(5) == "linear route reverse-route ___knil(node, node) generated");
  BOOST_REQUIRE(c.rules() == 3u);
  BOOST_TEST(c.rule(0) == "link(X0, X1) -o ___knil(X1, X0) (generated)");
  BOOST_TEST(c.rule(1) == "___knil(B, A), token(B, N) -o __mangledname1(A, N) (generated)");
  BOOST_TEST(c.rule(2) == "__mangledname1(A, N), !middle(A) -o !got(A, N)");
}

// Extra route arguments travel in the inverse; conditions go to the side whose variables they
// use; helper variables: ints first, then the others, each in order of first occurrence.
BOOST_AUTO_TEST_CASE(route_with_extra_arguments_and_helper_variable_order) {
  Compiled c(
      "type route link(node, node, int, float).\n"
      "type val(node, int, list int).\n"
      "type mine(node, int).\n"
      "type out(node, list int, float, int, int).\n"
      "!link(A, B, W, F), !val(B, V, L), !mine(A, M), V > W, M < V, Z = W + 1 -o !out(A, L, F, Z, M).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.preds() == 6u);
  BOOST_TEST(c.pred(4) == "__mangledname1(node, int, int, float, list int) generated");
  BOOST_TEST(c.pred(5) == "route reverse-route ___knil(node, node, int, float) generated");
  BOOST_REQUIRE(c.rules() == 3u);
  BOOST_TEST(c.rule(0) == "!link(X0, X1, X2, X3) -o !___knil(X1, X0, X2, X3) (generated)");
  BOOST_TEST(c.rule(1) ==
             "!___knil(B, A, W, F), !val(B, V, L), (V > W), (Z = (W + 1)) -o !__mangledname1(A, V, Z, F, L) "
             "(generated)");
  BOOST_TEST(c.rule(2) == "!__mangledname1(A, V, Z, F, L), !mine(A, M), (M < V) -o !out(A, L, F, Z, M)");
}

// One inverse route (and rule) per route predicate; helpers numbered in rule order.
BOOST_AUTO_TEST_CASE(inverse_route_is_generated_once) {
  Compiled c(std::string(kNeighbor) +
             "type other(node).\n"
             "!neighbor(A, B), !ending(B), !middle(A) -o !nearEnding(A).\n"
             "!nearEnding(A) :- !neighbor(A, B), !middle(B).\n"
             "!neighbor(A, B), !middle(B), !ending(A) -o !other(A).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.preds() == 8u);
  BOOST_TEST(c.pred(5) == "__mangledname1(node) generated");
  BOOST_TEST(c.pred(6) == "__mangledname2(node) generated");
  BOOST_TEST(c.pred(7) == "route reverse-route ___robhgien(node, node) generated");
  BOOST_REQUIRE(c.rules() == 6u);
  BOOST_TEST(c.rule(0) == "!neighbor(X0, X1) -o !___robhgien(X1, X0) (generated)");
  BOOST_TEST(c.rule(1) == "!___robhgien(B, A), !ending(B) -o !__mangledname1(A) (generated)");
  BOOST_TEST(c.rule(2) == "!___robhgien(B, A), !middle(B) -o !__mangledname2(A) (generated)");
  BOOST_TEST(c.rule(3) == "!__mangledname1(A), !middle(A) -o !nearEnding(A)");
  BOOST_TEST(c.rule(4) == "!___robhgien(B, A), !middle(B) :- !nearEnding(A)");  // moved, still `:-`
  BOOST_TEST(c.rule(5) == "!__mangledname2(A), !ending(A) -o !other(A)");
}

// The inverse name reverses the declared spelling, whatever the spelling of the use.
BOOST_AUTO_TEST_CASE(inverse_name_keeps_the_declared_spelling) {
  Compiled c(
      "type route neighBor(node, node).\n"
      "type ending(node).\n"
      "type near(node).\n"
      "!neighbor(A, B), !ending(B) -o !near(A).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_TEST(c.pred(3) == "route reverse-route ___roBhgien(node, node) generated");
  BOOST_TEST(c.rule(0) == "!neighBor(X0, X1) -o !___roBhgien(X1, X0) (generated)");
  BOOST_TEST(c.rule(1) == "!___roBhgien(B, A), !ending(B) -o !near(A)");
}

// Two route edges from the host: one helper each, joined at the host.
BOOST_AUTO_TEST_CASE(two_neighbours_get_one_helper_each) {
  Compiled c(std::string(kNeighbor) +
             "!neighbor(A, B), !neighbor(A, C), !ending(B), !middle(C) -o !nearEnding(A).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.rules() == 4u);
  BOOST_TEST(c.rule(1) == "!___robhgien(B, A), !ending(B) -o !__mangledname1(A) (generated)");
  BOOST_TEST(c.rule(2) == "!___robhgien(C, A), !middle(C) -o !__mangledname2(A) (generated)");
  BOOST_TEST(c.rule(3) == "!__mangledname1(A), !__mangledname2(A) -o !nearEnding(A)");
}

BOOST_AUTO_TEST_CASE(a_chain_of_route_hops_is_localized_hop_by_hop) {
  // Moved to B, where C is still a neighbour away: C's part becomes a helper sent to B.
  Compiled c(std::string(kNeighbor) + "!neighbor(A, B), !neighbor(B, C), !ending(C) -o !nearEnding(A).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.rules() == 3u);
  BOOST_TEST(c.rule(1) == "!___robhgien(C, B), !ending(C) -o !__mangledname1(B) (generated)");
  BOOST_TEST(c.rule(2) == "!__mangledname1(B), !___robhgien(B, A) -o !nearEnding(A)");
}

BOOST_AUTO_TEST_CASE(split_parts_are_localized_again_depth_first) {
  Compiled c(std::string(kNeighbor) +
             "!middle(A), !neighbor(A, B), !neighbor(B, C), !ending(C) -o !nearEnding(A).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_REQUIRE(c.rules() == 4u);
  BOOST_TEST(c.rule(1) == "!___robhgien(C, B), !ending(C) -o !__mangledname2(B) (generated)");
  BOOST_TEST(c.rule(2) == "!__mangledname2(B), !___robhgien(B, A) -o !__mangledname1(A) (generated)");
  BOOST_TEST(c.rule(3) == "!__mangledname1(A), !middle(A) -o !nearEnding(A)");
}

// Without bodies spanning nodes (a route used only at the host included) nothing changes.
BOOST_AUTO_TEST_CASE(programs_without_multi_node_bodies_are_unchanged) {
  Compiled c(
      "type route edge(node, node, int).\n"
      "type path(node, min int, list node).\n"
      "type linear start(node).\n"
      "edge(@0, @1, 4). edge(@1, @0, 2).\n"
      "start(@0).\n"
      "start(A) -o !path(A, 0, [A]).\n"
      "!path(B, D + W, [B | P]) :- !edge(A, B, W), !path(A, D, P).\n");
  BOOST_REQUIRE_MESSAGE(c.ok(), c.errors());
  BOOST_TEST(c.preds() == 3u);
  BOOST_TEST(c.rules() == 5u);
  const std::string before = c.dump();
  BOOST_TEST(before.find("generated") == std::string::npos);
  localizeRules(*c.program, c.diag);  // again, on the front end's output: still nothing to do
  BOOST_TEST(c.dump() == before);
  BOOST_TEST(!c.diag.hasErrors());
}
