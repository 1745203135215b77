#define BOOST_TEST_MODULE meldc_parser
#include <boost/test/unit_test.hpp>

#include "test_support.hpp"

using namespace meldc;
using namespace meldc::ast;

BOOST_AUTO_TEST_SUITE(declarations)

BOOST_AUTO_TEST_CASE(predicate_modifiers_and_fields) {
  Parsed p(
      "type edge(node, node, int).\n"
      "type linear route link(node, node Other).\n"
      "type route linear action beep(node, int).\n"
      "type path(node, min int, list node).\n"
      "type linear work(thread, list list int, :(int, float), array float, set int).\n");
  BOOST_REQUIRE(p.ok());
  const auto& preds = p.program->predicates;
  BOOST_REQUIRE_EQUAL(preds.size(), 5u);
  BOOST_TEST(!preds[0].linear);
  BOOST_TEST(preds[1].linear);
  BOOST_TEST(preds[1].route);
  BOOST_TEST(preds[1].fields[1].argName == "Other");
  BOOST_TEST((preds[2].linear && preds[2].route && preds[2].action));
  BOOST_TEST((preds[3].fields[1].agg == FieldAgg::Min));
  BOOST_TEST(toString(preds[3].fields[2].type) == "list node");
  BOOST_TEST(toString(preds[4].fields[1].type) == "list list int");
  BOOST_TEST(toString(preds[4].fields[2].type) == ":(int, float)");
  BOOST_TEST(toString(preds[4].fields[3].type) == "array float");
  BOOST_TEST(toString(preds[4].fields[4].type) == "set int");
  BOOST_TEST((preds[4].fields[0].type.kind == TypeKind::Thread));
}

BOOST_AUTO_TEST_CASE(aggregate_field_modifiers) {
  Parsed p("type a(node, max float). type b(node, sum list float). type c(node, first int, int).\n");
  BOOST_REQUIRE(p.ok());
  BOOST_TEST((p.program->predicates[0].fields[1].agg == FieldAgg::Max));
  BOOST_TEST((p.program->predicates[1].fields[1].agg == FieldAgg::Sum));
  BOOST_TEST((p.program->predicates[2].fields[1].agg == FieldAgg::First));
}

BOOST_AUTO_TEST_CASE(node_types_aliases_import_export) {
  Parsed p(
      "node page.\n"
      "type int number.\n"
      "type number number2.\n"
      "type linear rank(page, number2).\n"
      "import linear foo(node, int) as bar from libfile.\n"
      "export rank.\n");
  BOOST_REQUIRE(p.ok());
  BOOST_TEST(p.program->nodeTypes.at(0).name == "page");
  BOOST_TEST(p.program->typeAliases.at(1).name == "number2");
  BOOST_TEST(toString(p.program->typeAliases.at(1).type) == "number");
  BOOST_TEST(p.program->predicates.at(0).fields.at(0).type.name == "page");
  const auto& imp = p.program->predicates.at(1);
  BOOST_TEST(imp.imported);
  BOOST_TEST(imp.name == "bar");
  BOOST_TEST(imp.importedName == "foo");
  BOOST_TEST(imp.importedFrom == "libfile");
  BOOST_TEST(p.program->exports.at(0).name == "rank");
}

BOOST_AUTO_TEST_CASE(directives) {
  Parsed p(
      "type linear p(node, int).\n"
      "index p/2.\n"
      "compact p.\n"
      "data stanford-snap \"graph.txt\".\n"
      "data stanford-snap-search \"g.txt\" [\"1\" \"2\"].\n"
      "allocator \"basic\".\n"
      "priority @order @asc.\n"
      "priority @initial 1.5.\n"
      "priority @default -2.\n"
      "priority @no_priority 0.\n"
      "priority @static.\n"
      "priority @cluster @static.\n"
      "priority @cluster @random.\n"
      "priority @no_initial_priorities.\n"
      "priority p < p.\n");
  BOOST_REQUIRE(p.ok());
  const auto& d = p.program->directives;
  BOOST_REQUIRE_EQUAL(d.size(), 14u);
  BOOST_TEST((d[0].kind == DirectiveKind::Index && d[0].name == "p" && d[0].position == 2));
  BOOST_TEST((d[1].kind == DirectiveKind::Compact));
  BOOST_TEST((d[2].kind == DirectiveKind::Data && d[2].name == "stanford-snap" && d[2].text == "graph.txt"));
  BOOST_TEST(d[3].dataArgs.size() == 2u);
  BOOST_TEST((d[4].kind == DirectiveKind::Allocator && d[4].text == "basic"));
  BOOST_TEST((d[5].priority == PriorityKind::OrderAsc));
  BOOST_TEST((d[6].priority == PriorityKind::Initial && d[6].value == 1.5));
  BOOST_TEST((d[7].priority == PriorityKind::Default && d[7].value == -2.0));
  BOOST_TEST((d[8].priority == PriorityKind::NoPriority));
  BOOST_TEST((d[9].priority == PriorityKind::Static));
  BOOST_TEST((d[10].priority == PriorityKind::ClusterStatic));
  BOOST_TEST((d[11].priority == PriorityKind::ClusterRandom));
  BOOST_TEST((d[12].priority == PriorityKind::NoInitial));
  BOOST_TEST((d[13].priority == PriorityKind::Lower && d[13].other == "p"));
}

BOOST_AUTO_TEST_CASE(extern_const_fun) {
  Parsed p(
      "extern int myfun(int, float).\n"
      "const damping = 0.85.\n"
      "const epsilon = str2float(@arg1).\n"
      "const startnode = @4.\n"
      "const tosort = [3, 1, 2].\n"
      "fun next(int X) : int = if X <> 1 then 1 else 2 end.\n"
      "fun twice(int X, float Y) : float = let Z = float(X) in Z * Y end.\n");
  BOOST_REQUIRE(p.ok());
  BOOST_TEST(p.program->externs.at(0).name == "myfun");
  BOOST_TEST(p.program->externs.at(0).params.size() == 2u);
  BOOST_TEST(toString(p.program->consts.at(0).value) == "0.85");
  BOOST_TEST(toString(p.program->consts.at(1).value) == "str2float(@arg1)");
  BOOST_TEST(toString(p.program->consts.at(2).value) == "@4");
  BOOST_TEST(toString(p.program->consts.at(3).value) == "[3, 1, 2]");
  BOOST_TEST(toString(p.program->funs.at(0).body) == "if (X <> 1) then 1 else 2 end");
  BOOST_TEST(toString(p.program->funs.at(1).body) == "let Z = float(X) in (Z * Y) end");
  BOOST_TEST(p.program->funs.at(1).params.at(1).name == "Y");
}

BOOST_AUTO_TEST_CASE(includes_are_listed) {
  Parsed p("include #lib/colors.meld\ninclude #other.meld   // a comment\ntype p(node).\n");
  BOOST_REQUIRE(p.ok());
  BOOST_REQUIRE_EQUAL(p.program->includes.size(), 2u);
  BOOST_TEST(p.program->includes[0].path == "lib/colors.meld");
  BOOST_TEST(p.program->includes[1].path == "other.meld");
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(statements)

BOOST_AUTO_TEST_CASE(rule_forms) {
  Parsed p(
      "a(A, N), N > 0 -o b(A, N - 1).\n"
      "!path(A, B) :- !edge(A, C), !path(C, B).\n"
      "f(A) -o 1.\n"
      "f(A) -o .\n"
      ":- g(A).\n"
      "edge(@1, @2). a(@0, [1, 2]).\n"
      "!neighbor(@2, @3), !neighbor(@3, @2).\n");
  BOOST_REQUIRE(p.ok());
  const auto& r = p.program->rules;
  BOOST_REQUIRE_EQUAL(r.size(), 8u);
  BOOST_TEST((r[0].kind == RuleKind::Linear));
  BOOST_TEST(bodyItem(p, 0, 1) == "(N > 0)");
  BOOST_TEST(headItem(p, 0, 0) == "b(A, (N - 1))");
  BOOST_TEST((r[1].kind == RuleKind::Datalog));
  BOOST_TEST(headItem(p, 1, 0) == "!path(A, B)");
  BOOST_TEST(r[1].body.size() == 2u);
  BOOST_TEST(r[2].head.empty());
  BOOST_TEST(r[3].head.empty());
  BOOST_TEST((r[4].kind == RuleKind::Datalog && r[4].head.empty()));
  BOOST_TEST((r[5].kind == RuleKind::Fact));
  BOOST_TEST(headItem(p, 6, 0) == "a(@0, [1, 2])");
  BOOST_TEST(r[7].head.size() == 2u);
}

BOOST_AUTO_TEST_CASE(marks_and_delays) {
  Parsed p("!a(A), ?b(A), $c(A) -o d(A)@+500ms, e(A)@+2s.\nbubble(X, 5)@+500ms :- !vacant(X, 0).\n");
  BOOST_REQUIRE(p.ok());
  const auto& body = p.rule(0).body;
  BOOST_TEST((body[0].mark == Mark::Persistent));
  BOOST_TEST((body[1].mark == Mark::Linear));
  BOOST_TEST((body[2].mark == Mark::Reuse));
  BOOST_TEST(*p.rule(0).head[0].delayMs == 500);
  BOOST_TEST(*p.rule(0).head[1].delayMs == 2000);
  BOOST_TEST(*p.rule(1).head[0].delayMs == 500);
}

BOOST_AUTO_TEST_CASE(selectors) {
  Parsed p("[:min W | b(A), a(A, W)] -o c(A, W).\n[:random X | candidate(A, X), tok(A)] -o chosen(A, X).\n");
  BOOST_REQUIRE(p.ok());
  BOOST_TEST((p.rule(0).selector->kind == SelectorKind::Min));
  BOOST_TEST(p.rule(0).selector->var == "W");
  BOOST_TEST(p.rule(0).body.size() == 2u);
  BOOST_TEST((p.rule(1).selector->kind == SelectorKind::Random));
}

BOOST_AUTO_TEST_CASE(comprehensions) {
  Parsed p(
      "visit(A), unvisited(A) -o {B | !edge(A, B) | visit(B)}, visited(A).\n"
      "g(T, N) -o {T2, Id | !other(T, T2, Id) | coiso(T2, 1)}.\n"
      "h(A) -o {B | !edge(A, B) | }.\n");
  BOOST_REQUIRE(p.ok());
  BOOST_TEST(headItem(p, 0, 0) == "{B | !edge(A, B) | visit(B)}");
  BOOST_TEST(p.rule(1).head[0].vars.size() == 2u);
  BOOST_TEST(headItem(p, 2, 0) == "{B | !edge(A, B) | 1}");
}

BOOST_AUTO_TEST_CASE(aggregate_shapes) {
  Parsed p(
      "a(A, X) -o [collect => L | b(A, L) | c(A, L)].\n"                 // A
      "a(A, X) -o [collect => L | b(A, L) | | c(A, L)].\n"               // B
      "s(A) -o [count => C | B | !output(A, B) | !numLinks(A, C)].\n"    // C
      "a(A, N) -o [sum => Y | Y1 | b(A, Y) | Y1 = Y + 1 | c(A, Y1)].\n"  // D
      "a(A, N) -o [sum => Y | B | b(A, B, Y) | | c(A, Y)].\n"            // E
      "a(A, X) -o [collect => L | b(A, L) | d(A, L) | c(A, L)].\n"       // F
      "a(A) -o [min => W | B | b(A, B, W)].\n"                           // G
      "a(A) -o [custom add 0 => W, count => C | b(A, W) | c(A, W, C)].\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  const AggShape shapes[] = {AggShape::A, AggShape::B, AggShape::C, AggShape::D,
                             AggShape::E, AggShape::F, AggShape::G, AggShape::A};
  for (size_t i = 0; i < 8; ++i) {
    BOOST_TEST_CONTEXT("rule " << i) {
      BOOST_TEST((p.rule(i).head.at(0).kind == TermKind::Aggregate));
      BOOST_TEST((p.rule(i).head.at(0).shape == shapes[i]));
    }
  }
  const Term& d = p.rule(3).head[0];
  BOOST_TEST(d.vars.at(0).name == "Y1");
  BOOST_TEST(toString(d.perMatch.at(0)) == "(Y1 = (Y + 1))");
  BOOST_TEST(toString(d.head.at(0)) == "c(A, Y1)");
  const Term& custom = p.rule(7).head[0];
  BOOST_TEST((custom.specs.at(0).op == AggOp::Custom));
  BOOST_TEST(custom.specs.at(0).function == "add");
  BOOST_TEST((custom.specs.at(1).op == AggOp::Count));
}

BOOST_AUTO_TEST_CASE(exists_and_conditionals) {
  Parsed p(
      "build(A, X) -o exists B, C. (back(B, A), down(C, X)).\n"
      "u(A, Diff) -o {B, W | !edge(A, B, W) | n(B), (if Diff > epsilon then update(B) otherwise 1 end)}.\n");
  BOOST_REQUIRE(p.ok());
  const Term& e = p.rule(0).head.at(0);
  BOOST_TEST((e.kind == TermKind::Exists));
  BOOST_TEST(e.vars.size() == 2u);
  BOOST_TEST(e.head.size() == 2u);
  const Term& c = p.rule(1).head.at(0).head.at(1);
  BOOST_TEST((c.kind == TermKind::Conditional));
  BOOST_TEST(toString(c.cond) == "(Diff > epsilon)");
  BOOST_TEST(c.head.size() == 1u);
  BOOST_TEST(c.elseHead.empty());
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(expressions)

// The expression of the constraint in `a(A) -o b(A), <text>.`
static std::string exprOf(const std::string& text) {
  Parsed p("a(A) -o " + text + ".\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  return headItem(p, 0, 0);
}

BOOST_AUTO_TEST_CASE(precedence) {
  BOOST_TEST(exprOf("X = 1 + 2 * 3") == "(X = (1 + (2 * 3)))");
  BOOST_TEST(exprOf("X = (1 + 2) * 3") == "(X = ((1 + 2) * 3))");
  BOOST_TEST(exprOf("X = 1 - 2 - 3") == "(X = ((1 - 2) - 3))");
  BOOST_TEST(exprOf("X = L1 ++ L2 ++ L3") == "(X = ((L1 ++ L2) ++ L3))");
  BOOST_TEST(exprOf("X = N % 8 + 1") == "(X = ((N % 8) + 1))");
  BOOST_TEST(exprOf("A < B || C < D && E < F") == "((A < B) || ((C < D) && (E < F)))");
  BOOST_TEST(exprOf("A < B && C < D && E < F") == "((A < B) && ((C < D) && (E < F)))");
  BOOST_TEST(exprOf("~ A < B && C < D") == "(~(A < B) && (C < D))");
  BOOST_TEST(exprOf("(A < B || C < D) && E < F") == "(((A < B) || (C < D)) && (E < F))");
}

BOOST_AUTO_TEST_CASE(minus_superset) {
  // cl-meld lexes X-1 as X and -1 (a parse error); we accept it as a subtraction (spec §11).
  BOOST_TEST(exprOf("Y = X-1") == "(Y = (X - 1))");
  BOOST_TEST(exprOf("Y = 5-1") == "(Y = (5 - 1))");
  BOOST_TEST(exprOf("Y = -3") == "(Y = -3)");
  BOOST_TEST(exprOf("Y = X - -3") == "(Y = (X - -3))");
  BOOST_TEST(exprOf("Y = -0.5 * X") == "(Y = (-0.5 * X))");
}

BOOST_AUTO_TEST_CASE(literals_and_specials) {
  BOOST_TEST(exprOf("X = [1, 2 | T]") == "(X = [1, 2 | T])");
  BOOST_TEST(exprOf("X = []") == "(X = [])");
  BOOST_TEST(exprOf("X = nil") == "(X = nil)");
  BOOST_TEST(exprOf("X = :(1, 2.5, Y)") == "(X = :(1, 2.5, Y))");
  BOOST_TEST(exprOf("X = \"text\"") == "(X = \"text\")");
  BOOST_TEST(exprOf("X = true") == "(X = true)");
  BOOST_TEST(exprOf("X = @world + @cpus") == "(X = (@world + @cpus))");
  BOOST_TEST(exprOf("X = @host") == "(X = @host)");
  BOOST_TEST(exprOf("X = @thread") == "(X = @thread)");
  BOOST_TEST(exprOf("X = str2int(@arg3)") == "(X = str2int(@arg3))");
  BOOST_TEST(exprOf("X = @ 7") == "(X = @7)");
  BOOST_TEST(exprOf("X = float(N) / 2.0") == "(X = (float(N) / 2.0))");
  BOOST_TEST(exprOf("X in L") == "(X in L)");
  BOOST_TEST(exprOf("L1 ins L2") == "(L1 ins L2)");
  BOOST_TEST(exprOf("X = if N >= 0 then N else 0 - N end") == "(X = if (N >= 0) then N else (0 - N) end)");
  BOOST_TEST(exprOf("X = let Y = N * 2 in Y + Y end") == "(X = let Y = (N * 2) in (Y + Y) end)");
  BOOST_TEST(exprOf("X = _") == "(X = _)");
  BOOST_TEST(exprOf("X = damping") == "(X = damping)");
}

BOOST_AUTO_TEST_CASE(float_literals_keep_their_spelling) {
  Parsed p("const a = 3.14.\nconst b = 1.\n");
  BOOST_REQUIRE(p.ok());
  BOOST_TEST(p.program->consts[0].value.text == "3.14");
  BOOST_TEST((p.program->consts[0].value.kind == ExprKind::Float));
  BOOST_TEST((p.program->consts[1].value.kind == ExprKind::Int));  // `1.` is 1 then end of statement
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(lexical)

BOOST_AUTO_TEST_CASE(keywords_are_case_insensitive) {
  Parsed p("TYPE LINEAR a(NODE, INT).\n");  // upper-case start: variables, so a syntax error
  BOOST_TEST(!p.ok());
  Parsed q("tYPE lINEAR a(nODE, iNT).\n");
  BOOST_REQUIRE_MESSAGE(q.ok(), q.errors());
  BOOST_TEST(q.program->predicates.at(0).linear);
}

BOOST_AUTO_TEST_CASE(identifiers_with_dashes_and_question_marks) {
  Parsed p("type neighbor-level(node, int).\ntype a?(node).\nneighbor-level(A, n-1) -o a?(A).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.program->predicates.at(0).name == "neighbor-level");
  BOOST_TEST(p.program->predicates.at(1).name == "a?");
  BOOST_TEST(bodyItem(p, 0, 0) == "neighbor-level(A, n-1)");  // n-1 is one name (a constant)
}

BOOST_AUTO_TEST_CASE(quoted_identifiers_and_anonymous_variables) {
  Parsed p("type 'Odd(node, int).\n'Odd(A, _), 'Odd(A, _) -o 1.\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.program->predicates.at(0).name == "'Odd");
  BOOST_TEST(bodyItem(p, 0, 1) == "'Odd(A, _)");
}

BOOST_AUTO_TEST_CASE(comments) {
  Parsed p(
      "// a line comment\n"
      "type a(node). /* one line */ type b(node).\n"
      "/* several\n"
      "   lines */\n"
      "a(A) -o b(A). // trailing\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.program->predicates.size() == 2u);
  BOOST_TEST(p.program->rules.size() == 1u);
}

BOOST_AUTO_TEST_CASE(header_words_as_names) {
  Parsed p("type data(node, int).\ndata(A, N) -o index(A, N).\n");
  // `index` is only a keyword in the header; we accept it as a name everywhere.
  BOOST_TEST(p.program.has_value());
}

BOOST_AUTO_TEST_CASE(stray_characters_are_skipped_with_a_warning) {
  Parsed p("type a(node). ;\n");
  BOOST_TEST(p.ok());
  BOOST_TEST(p.diag.warningCount() == 1);
  BOOST_TEST(p.errors().find("ignoring stray character ';'") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(locations)

BOOST_AUTO_TEST_CASE(every_node_has_a_location) {
  Parsed p("type a(node, int).\n\n  a(A, N),\n    N > 0 -o a(A, N - 1).\n");
  BOOST_REQUIRE(p.ok());
  const auto& pred = p.program->predicates.at(0);
  BOOST_TEST((pred.loc == SourceLoc{0, 1, 1}));
  BOOST_TEST((pred.nameLoc == SourceLoc{0, 1, 6}));
  BOOST_TEST((pred.fields.at(1).loc == SourceLoc{0, 1, 14}));
  const Rule& r = p.rule(0);
  BOOST_TEST((r.loc == SourceLoc{0, 3, 3}));
  BOOST_TEST((r.body.at(0).loc == SourceLoc{0, 3, 3}));
  BOOST_TEST((r.body.at(0).args.at(1).loc == SourceLoc{0, 3, 8}));
  BOOST_TEST((r.body.at(1).loc == SourceLoc{0, 4, 5}));
  BOOST_TEST((r.body.at(1).cond.loc == SourceLoc{0, 4, 7}));  // the operator
  const Expr& minus = r.head.at(0).args.at(1);
  BOOST_TEST((minus.loc == SourceLoc{0, 4, 21}));
  BOOST_TEST((minus.args.at(0).loc == SourceLoc{0, 4, 19}));
  BOOST_TEST((minus.args.at(1).loc == SourceLoc{0, 4, 23}));
}

BOOST_AUTO_TEST_SUITE_END()
