// Ground facts (ast/ground_fact.hpp): facts of literals only take a compact path from the parser
// to the axiom blocks. Whatever path a fact takes, the compiler must say and produce exactly what
// it does with every fact parsed by ANTLR: same diagnostics, same AST dump, same bytecode.
#define BOOST_TEST_MODULE meldc_ground_facts
#include <boost/test/unit_test.hpp>
#include <sstream>

#include "meldc/ast_dump.hpp"
#include "meldc/frontend.hpp"
#include "meldc/ground_facts.hpp"
#include "meldc/lower.hpp"
#include "meldvm/bytecode.hpp"
#include "temp_dir.hpp"

namespace {

struct Compiled {
  std::string messages;
  std::string ast;  // the AST dump, every fact as a statement
  std::string asmText;
  std::size_t groundFacts = 0;  // facts left on the compact path
};

// `files`: name -> text; the first is the main file.
Compiled compile(const std::vector<std::pair<std::string, std::string>>& files, bool groundFacts,
                 bool robots = false) {
  TempDir dir;
  std::string main;
  for (const auto& [name, text] : files) {
    std::string path = dir.write(name, text);
    if (main.empty()) main = path;
  }
  meldc::SourceManager sources;
  std::ostringstream messages;
  meldc::Diagnostics diag(sources, messages);
  meldc::FrontEndInput input{main, {}, {}};
  input.groundFacts = groundFacts;
  input.identityNodes = robots;
  Compiled out;
  std::optional<meldc::ast::Program> ast = meldc::runFrontEnd(input, sources, diag);
  if (ast) {
    out.groundFacts = ast->groundFacts.facts.size();
    std::unique_ptr<meldvm::Program> program = meldc::lowerProgram(*ast, sources, diag);
    if (program) {
      std::ostringstream text;
      meldvm::disassemble(*program, text);
      out.asmText = text.str();
    }
    meldc::materializeGroundFacts(*ast, sources);
    std::ostringstream dump;
    meldc::dumpProgram(*ast, sources, dump);
    out.ast = dump.str();
  }
  // The temporary folder's name differs between the two compilations.
  out.messages = messages.str();
  for (std::string* text : {&out.messages, &out.ast})
    for (std::size_t at; (at = text->find(dir.path.string())) != std::string::npos;)
      text->replace(at, dir.path.string().size(), "DIR");
  return out;
}

// Compiles both ways and checks that nothing differs; returns the compact compilation.
Compiled same(const std::vector<std::pair<std::string, std::string>>& files, bool robots = false) {
  Compiled compact = compile(files, true, robots);
  Compiled plain = compile(files, false, robots);
  BOOST_TEST(compact.messages == plain.messages);
  BOOST_TEST(compact.ast == plain.ast);
  BOOST_TEST(compact.asmText == plain.asmText);
  BOOST_TEST(plain.groundFacts == 0u);
  return compact;
}

Compiled same(const std::string& text, bool robots = false) { return same({{"main.meld", text}}, robots); }

const char* kGraph = R"(type route edge(node, node, int).
type path(node, min int).
type linear weight(node, float, string, bool).
!path(A, D), !edge(A, B, W) -o !path(B, D + W).
)";

}  // namespace

BOOST_AUTO_TEST_CASE(literal_facts_take_the_compact_path_with_the_same_bytecode) {
  Compiled c = same(std::string(kGraph) +
                    "!path(@5, 0).\n!edge(@5, @2, 3). !edge(@2, @9, -4).\n"
                    "weight(@9, 1.5, \"heavy\", true). weight(@2, 2, \"\", false).\n"
                    "!edge(@9,\n   @5, 7).\n");
  BOOST_TEST(c.messages.empty());
  BOOST_TEST(c.groundFacts == 6u);
  BOOST_TEST(c.asmText.find("DERIVE") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(literal_facts_pack_into_axiom_facts_the_same_way_on_both_paths) {
  // AXIOM_FACTS runs: ground facts and statements that fold to literals (a const) in one run,
  // ints for a float field, negative ints, bools. A computed fact (2 + k) comes first by DERIVE
  // (§6.2: evaluated axioms, then the literal ones by predicate), and the string-field facts after
  // the run, by DERIVE; facts of other nodes go to their own blocks.
  Compiled c = same(R"(type linear m(node, int, float, bool, node).
type linear s(node, string).
const k = 2.
m(@1, -7, 2, true, @2). m(@1, k, 0.5, false, @1). m(@1, 3, -1.25, true, @3).
s(@1, "cut").
m(@1, 4, 1.0, false, @1). m(@1, 2 + k, 1.0, false, @1). m(@1, 5, 1.0, false, @1).
m(@2, 6, 6.5, true, @1). s(@2, "x"). m(@3, 2147483647, -0.0, false, @3).
)");
  BOOST_TEST(c.messages.empty());
  // (2 + k folds to 4 at compile time, but the fact stays an evaluated one, first.)
  BOOST_TEST(c.asmText.find("MOVI      r0 4\n") != std::string::npos, c.asmText);
  BOOST_TEST(c.asmText.find("DERIVE    p=m(4) (r0, r1, r2, r3)\n  0020  AXIOM_FACTS p=m(4) 5 facts\n"
                            "                 (-7, 2, true, @") != std::string::npos,
             c.asmText);
  BOOST_TEST(c.asmText.find("(2147483647, -0, false, @") != std::string::npos, c.asmText);
}

BOOST_AUTO_TEST_CASE(facts_between_rules_keep_their_place) {
  // Node numbering (§6.1) and the order of axioms depend on where every literal stands.
  Compiled c = same(R"(type route edge(node, node).
type linear a(node, int).
type linear b(node, int).
a(@7, 1).
a(X, N) -o b(X, N).
!edge(@3, @7). b(@3, 2). a(@3, 3).
b(X, N), N > 1, !edge(X, Y) -o a(Y, N - 1).
a(@1, 4). !edge(@7, @1).
)");
  BOOST_TEST(c.messages.empty());
  BOOST_TEST(c.groundFacts == 6u);
}

BOOST_AUTO_TEST_CASE(facts_the_checks_must_see_are_statements_again) {
  // Wrong mark, unknown predicate, wrong arity, wrong literal type, a built-in instruction, a
  // node subtype: the usual messages, at the usual places.
  Compiled c = same(R"(node page.
type linear a(node, int).
type route link(page, page).
type c(node, int).
!a(@1, 2).
d(@1, 2).
c(@1).
set-priority(@1, 2.0).
link(@1, @2).
c(@1, 3).
)");
  BOOST_TEST(c.messages.find("main.meld:5:1: error: 'a' is linear") != std::string::npos);
  BOOST_TEST(c.messages.find("main.meld:6:1: error: unknown predicate 'd'") != std::string::npos);
  BOOST_TEST(c.messages.find("main.meld:7:1: error: predicate 'c' takes 2 arguments") != std::string::npos);
  Compiled types = same("type c(node, int).\nc(@1, 2.5).\nc(@1, \"s\").\n");
  BOOST_TEST(types.messages.find("main.meld:2:7: error") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(only_plain_facts_stay_compact) {
  Compiled c = same(R"(node page.
type route link(page, page).
type linear a(node, int).
type action blink(node, int).
link(@1, @2).
a(@1, 3).
a(@2, 4).
)");
  BOOST_TEST(c.messages.empty());
  BOOST_TEST(c.groundFacts == 2u);  // `link` has a subtype home: the type checker's business
}

BOOST_AUTO_TEST_CASE(section_order_is_checked_across_ground_facts) {
  Compiled c = same("type linear a(node, int).\na(@1, 2).\ntype linear b(node).\n");
  BOOST_TEST(c.messages.find("type declaration after rules and facts") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(what_the_scanner_leaves_to_antlr) {
  // A comment inside a fact, a constant argument, a '-' apart from its number, `exists X.`
  // whose '.' ends no statement, an include path with dots, non-ASCII text before a fact on its
  // line (columns count characters), a fact on the line of a rule.
  Compiled c = same({{"main.meld", R"(include #lib.v1.meld
type linear a(node, int).
type linear n(node, node).
const k = 4.
a(@1, /* one */ 1).
a(@2, k).
a(@3, - 5).
a(X, N), N > 0 -o exists Y. (n(X, Y), a(Y, N - 1)).
/* é */ a(@4, 6). a(@5, 7). a(A, 1) -o 1.
)"},
                     {"lib.v1.meld", "type linear q(node, int).\nq(@9, 1).\n"}});
  BOOST_TEST(c.messages.empty());
  BOOST_TEST(c.groundFacts == 3u);  // a(@4), a(@5) and the included q(@9)
}

BOOST_AUTO_TEST_CASE(messages_about_other_statements_keep_their_columns) {
  Compiled c = same("type linear a(node, int).\na(@1, 1). a(@2, 2). a(X, N) -o b(X).\n");
  BOOST_TEST(c.messages.find("main.meld:2:32: error: unknown predicate 'b'") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(syntax_errors_are_reported_on_the_whole_text) {
  Compiled c = same("type linear a(node, int).\na(@1, 1).\na(@2, 2)\na(@3, 3).\na(@4, 4) a.\n");
  BOOST_TEST(c.messages.find("error") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(out_of_range_literals_are_the_parsers_business) {
  Compiled c =
      same("type linear a(node, int).\na(@1, 2147483648).\na(@2147483648, 1).\na(@1, -2147483648).\n");
  BOOST_TEST(c.messages.find("out of range") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(robots_number_nodes_by_their_ids) {
  Compiled c = same("type linear a(node, int).\na(@4, 1).\na(@2, 2).\na(X, N) -o 1.\n", true);
  BOOST_TEST(c.messages.empty());
  BOOST_TEST(c.groundFacts == 2u);
}

BOOST_AUTO_TEST_CASE(a_file_of_facts_only_is_not_empty) {
  Compiled c =
      same({{"main.meld", "include #decl.meld\n!e(@1, 2).\n"}, {"decl.meld", "type e(node, int).\n"}});
  BOOST_TEST(c.messages.empty());
  BOOST_TEST(c.groundFacts == 1u);
}
