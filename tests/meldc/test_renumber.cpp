#define BOOST_TEST_MODULE meldc_renumber
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "meldc/frontend.hpp"
#include "meldc/ground_facts.hpp"
#include "meldc/renumber.hpp"
#include "temp_dir.hpp"

using namespace meldc;
namespace fs = std::filesystem;

namespace {

// Runs the whole front end (as `meldc --check` does) on `main` of `files`.
struct Compiled {
  SourceManager sources;
  std::ostringstream messages;
  Diagnostics diag{sources, messages};
  std::optional<ast::Program> program;

  Compiled(const TempDir& files, const std::string& main) {
    program = runFrontEnd(FrontEndInput{(files.path / main).string(), {}, {}}, sources, diag);
    // Literal facts come out compact (ground_fact.hpp): as statements again, the tests read every
    // fact in `rules`.
    if (program) materializeGroundFacts(*program, sources);
  }
  bool ok() const { return program.has_value() && !diag.hasErrors(); }
  std::string errors() const { return messages.str(); }
  // "internal:source ..." of the node table.
  std::string table() const {
    std::ostringstream out;
    const char* sep = "";
    for (const ast::NodeId& n : program->nodeTable) {
      out << sep << n.internal << ':' << n.source;
      sep = " ";
    }
    return out.str();
  }
};

// One file programs.
struct Single : TempDir, Compiled {
  explicit Single(const std::string& text) : TempDir(), Compiled(init(text), "main.meld") {}
  const TempDir& init(const std::string& text) {
    write("main.meld", text);
    return *this;
  }
};

using Ids = std::vector<int64_t>;

}  // namespace

BOOST_AUTO_TEST_CASE(union_prepends_the_longer_list_onto_the_shorter) {
  BOOST_TEST(sbclUnion({}, {1, 2, 3}) == (Ids{3, 2, 1}));         // union([], Y) = reverse(Y)
  BOOST_TEST(sbclUnion({1, 2, 3}, {}) == (Ids{3, 2, 1}));         // and symmetrically
  BOOST_TEST(sbclUnion({1}, {2, 3, 1}) == (Ids{3, 2, 1}));        // X shorter: S = X
  BOOST_TEST(sbclUnion({1, 2, 3}, {4, 2}) == (Ids{3, 1, 4, 2}));  // Y shorter: S = Y
  BOOST_TEST(sbclUnion({1, 2}, {3, 4}) == (Ids{2, 1, 3, 4}));     // equal lengths: S = Y
  BOOST_TEST(sbclUnion({5, 6}, {6, 5}) == (Ids{6, 5}));           // same elements: S = Y
}

BOOST_AUTO_TEST_CASE(breadth_first_queue_algorithm) {
  BOOST_TEST(numberBreadthFirst({3, 2, 1}, {}) == (Ids{3, 2, 1}));
  BOOST_TEST(numberBreadthFirst({3, 2, 1}, {{1, {3, 2}}}) == (Ids{3, 2, 1}));
  // once E is empty the rest of P keeps its order, whatever is still queued
  BOOST_TEST(numberBreadthFirst({1, 2, 3}, {{1, {3, 2}}}) == (Ids{1, 2, 3}));
  BOOST_TEST(numberBreadthFirst({4, 1, 2, 3}, {{4, {3}}, {3, {2}}}) == (Ids{4, 3, 1, 2}));
  // 4 -> 3 -> 2 -> 5 with E not yet empty (5 has edges): the queue follows the edges
  BOOST_TEST(numberBreadthFirst({4, 1, 2, 3, 5}, {{4, {3}}, {3, {2}}, {2, {5}}, {5, {1}}}) ==
             (Ids{4, 3, 2, 5, 1}));
  BOOST_TEST(numberBreadthFirst({}, {}) == Ids{});
}

BOOST_AUTO_TEST_CASE(basic_example_without_routes) {
  Single p("type linear a(node, list node).\na(@0, [@1, @2]).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.table() == "0:2 1:1 2:0");
  const ast::Term& a = p.program->rules.at(0).head.at(0);
  BOOST_TEST(a.args[0].intValue == 2);
  BOOST_TEST(a.args[1].args[0].intValue == 1);
  BOOST_TEST(a.args[1].args[1].intValue == 0);
  BOOST_TEST(p.program->renumbered);
}

BOOST_AUTO_TEST_CASE(two_edge_example_with_a_route) {
  Single p("type route edge(node, node).\n!edge(@1, @2).\n!edge(@1, @3).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.table() == "0:3 1:2 2:1");
  const auto& rules = p.program->rules;
  BOOST_TEST(rules.at(0).head.at(0).args[0].intValue == 2);
  BOOST_TEST(rules.at(0).head.at(0).args[1].intValue == 1);
  BOOST_TEST(rules.at(1).head.at(0).args[0].intValue == 2);
  BOOST_TEST(rules.at(1).head.at(0).args[1].intValue == 0);
}

BOOST_AUTO_TEST_CASE(main_file_with_only_includes_reverses_the_included_literals) {
  TempDir f;
  f.write("lib.meld", "type linear p(node).\np(@5).\np(@7).\np(@6).\np(@5).\n");
  f.write("main.meld", "include #lib.meld\n");
  Compiled p(f, "main.meld");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // literals(lib) = [5 7 6]; nodes(main) = union([], [5 7 6]) = [6 7 5]; P = [5 7 6]
  BOOST_TEST(p.table() == "0:5 1:7 2:6");
}

BOOST_AUTO_TEST_CASE(nested_includes_merge_in_reverse_include_order) {
  TempDir f;
  f.write("c.meld", "p(@5).\n");
  f.write("a.meld", "include #c.meld\np(@2).\n");
  f.write("b.meld", "p(@3).\np(@4).\n");
  f.write("main.meld", "include #a.meld\ninclude #b.meld\ntype linear p(node).\np(@1).\n");
  Compiled p(f, "main.meld");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // nodes(a) = union([2], [5]) = [2 5] (equal lengths: S = [5]);
  // nodes(main) = union([1], [3 4]) = [4 3 1] (b first), then union([4 3 1], [2 5]) = [1 3 4 2 5];
  // P = [5 2 4 3 1]
  BOOST_TEST(p.table() == "0:5 1:2 2:4 3:3 4:1");
}

BOOST_AUTO_TEST_CASE(union_with_a_longer_included_list) {
  TempDir f;
  f.write("lib.meld", "p(@2).\np(@3).\np(@1).\n");
  f.write("main.meld", "include #lib.meld\ntype linear p(node).\np(@1).\n");
  Compiled p(f, "main.meld");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // union([1], [2 3 1]) = [3 2 1] -> P = [1 2 3]
  BOOST_TEST(p.table() == "0:1 1:2 2:3");
}

BOOST_AUTO_TEST_CASE(union_with_a_shorter_included_list) {
  TempDir f;
  f.write("lib.meld", "p(@9).\n");
  f.write("main.meld", "include #lib.meld\ntype linear p(node).\np(@1).\np(@2).\np(@9).\n");
  Compiled p(f, "main.meld");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // union([1 2 9], [9]) = [2 1 9] (S = [9], 1 then 2 prepended) -> P = [9 1 2]
  BOOST_TEST(p.table() == "0:9 1:1 2:2");
}

BOOST_AUTO_TEST_CASE(routes_in_several_components) {
  Single p(
      "type route e(node, node).\ntype linear v(node).\ntype linear w(node, node).\n"
      "v(@1). v(@2). v(@3). v(@8).\n"
      "e(@6, @8). e(@4, @1). e(@4, @3). e(@3, @2). e(@6, @7).\n"
      "w(@7, @2).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // P = [7 4 6 8 3 2 1]; E = {6: [7 8], 4: [3 1], 3: [2]} (w is not a route):
  // 7 (no edges), then 4 and its queue 3 1 2, then 6, and 8 once E is empty
  BOOST_TEST(p.table() == "0:7 1:4 2:3 3:1 4:2 5:6 6:8");
}

BOOST_AUTO_TEST_CASE(route_edges_only_from_constant_axioms) {
  Single p(
      "type route e(node, node).\ntype linear go(node).\n"
      "go(@1).\ngo(@2).\ngo(@3).\n"
      "go(A) -o e(A, @3).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // the rule head is no axiom: no edges, P order
  BOOST_TEST(p.table() == "0:3 1:2 2:1");
}

BOOST_AUTO_TEST_CASE(route_target_is_the_first_node_argument) {
  Single p(
      "type route r(node, int, node, node).\ntype linear v(node).\nv(@1). v(@2). v(@3).\nr(@1, 7, @2, "
      "@3).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // P = [3 2 1]; E = {1: [2]}: 3, then 2 (P), then 1
  BOOST_TEST(p.table() == "0:3 1:2 2:1");
  Single q(
      "type route r(node, int, node, node).\ntype linear v(node).\nv(@3). v(@2). v(@1).\nr(@3, 7, @1, "
      "@2).\n");
  BOOST_REQUIRE_MESSAGE(q.ok(), q.errors());
  // P = [1 2 3]; E = {3: [1]}: 1, 2, 3
  BOOST_TEST(q.table() == "0:1 1:2 2:3");
}

BOOST_AUTO_TEST_CASE(literals_in_constants_functions_bodies_and_heads) {
  Single p(
      "type linear a(node, node).\ntype linear b(node).\n"
      "const start = @5.\n"
      "fun pick(int X) : node = if X > 0 then @6 else @7 end.\n"
      "a(A, @8) -o b(@9), a(A, start).\n"
      "b(@5).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  // first occurrences 5 6 7 8 9 -> P = [9 8 7 6 5]
  BOOST_TEST(p.table() == "0:9 1:8 2:7 3:6 4:5");
  const ast::Program& prog = *p.program;
  BOOST_TEST(prog.consts.at(0).value.intValue == 4);
  BOOST_TEST(prog.funs.at(0).body.args.at(1).intValue == 3);
  BOOST_TEST(prog.funs.at(0).body.args.at(2).intValue == 2);
  BOOST_TEST(prog.rules.at(0).body.at(0).args.at(1).intValue == 1);
  BOOST_TEST(prog.rules.at(0).head.at(0).args.at(0).intValue == 0);
  BOOST_TEST(prog.rules.at(1).head.at(0).args.at(0).intValue == 4);
}

BOOST_AUTO_TEST_CASE(first_textual_occurrence_ignores_comments) {
  Single p("type linear b(node).\n// b(@1).\nb(@2). /* @3 */ b(@4).\nb(@1).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.table() == "0:1 1:4 2:2");
}

BOOST_AUTO_TEST_CASE(program_without_node_literals) {
  Single p("type linear b(node).\nb(A) -o b(A).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.program->nodeTable.empty());
}

BOOST_AUTO_TEST_CASE(cluster_static_keeps_source_ids) {
  Single p("type route e(node, node).\npriority @cluster @static.\ne(@3, @1).\n");
  BOOST_REQUIRE_MESSAGE(p.ok(), p.errors());
  BOOST_TEST(p.table() == "0:0 1:1 2:2 3:3");
  BOOST_TEST(p.program->rules.at(0).head.at(0).args[0].intValue == 3);
  BOOST_TEST(p.program->rules.at(0).head.at(0).args[1].intValue == 1);
}

BOOST_AUTO_TEST_CASE(cluster_random_is_a_reproducible_permutation) {
  const std::string text = "type linear a(node).\npriority @cluster @random.\na(@1). a(@2). a(@5). a(@7).\n";
  Single p(text), q(text);
  BOOST_TEST(p.ok(), p.errors());
  BOOST_TEST(p.table() == q.table());
  BOOST_TEST(p.table() == "0:2 1:5 2:7 3:1");  // the default numbering would give 0:7 1:5 2:2 3:1
}

BOOST_AUTO_TEST_CASE(data_directive_keeps_the_ids_of_the_file) {
  // §6.1: with `data` the node ids are those of the file; ids 0..max all exist.
  TempDir dir;
  dir.write("graph.txt", "# comment\n4\t1\n1\t0\n");
  dir.write("main.meld", "type edge(node, node).\ndata stanford-snap-basic \"graph.txt\".\n!edge(@1, @2).\n");
  Compiled p(dir, "main.meld");
  BOOST_TEST(p.ok(), p.errors());
  BOOST_TEST(p.table() == "0:0 1:1 2:2 3:3 4:4");
}

BOOST_AUTO_TEST_CASE(data_file_errors_name_the_file_and_line) {
  TempDir dir;
  dir.write("graph.txt", "0\t1\n1\tx\n");
  dir.write("main.meld", "type edge(node, node).\ndata stanford-snap-basic \"graph.txt\".\n");
  Compiled p(dir, "main.meld");
  BOOST_TEST(!p.ok());
  BOOST_TEST(p.errors().find("graph.txt:2: expected `source target`") != std::string::npos, p.errors());
  Single missing("type edge(node, node).\ndata stanford-snap \"nowhere.txt\".\n");
  BOOST_TEST(missing.errors().find("main.meld:2:1: error: cannot read the data file") != std::string::npos,
             missing.errors());
  Single unknown("type edge(node, node).\ndata stanford-nope \"g.txt\".\n");
  BOOST_TEST(unknown.errors().find("unknown data template 'stanford-nope'") != std::string::npos,
             unknown.errors());
}
