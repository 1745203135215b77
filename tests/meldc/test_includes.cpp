#define BOOST_TEST_MODULE meldc_includes
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include "meldc/frontend.hpp"
#include "meldc/includes.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace meldc;
namespace fs = std::filesystem;

namespace {

// The predicate names of the facts, in merged order.
std::string factOrder(const ast::Program& p) {
  std::string out;
  for (const ast::Rule& r : p.rules) out += (out.empty() ? "" : " ") + r.head.at(0).name;
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(merge_order_is_main_then_includes_reversed) {
  TempDir dir;
  dir.write("a.meld", "include #sub/c.meld\ntype a(node).\n!a(@1).\n");
  dir.write("sub/c.meld", "type c(node).\n!c(@3).\n");
  dir.write("b.meld", "type b(node).\n!b(@2).\n");
  std::string main = dir.write("main.meld", "include #a.meld\ninclude #b.meld\ntype m(node).\n!m(@0).\n");
  SourceManager sources;
  std::ostringstream err;
  Diagnostics diag(sources, err);
  auto program = loadProgram(main, {}, sources, diag);
  BOOST_REQUIRE_MESSAGE(program && !diag.hasErrors(), err.str());
  BOOST_TEST(factOrder(*program) == "m b a c");
  BOOST_TEST(program->predicates.size() == 4u);
  BOOST_TEST(program->predicates[0].name == "m");
  BOOST_TEST(program->predicates[1].name == "b");
  // Locations name the file they come from.
  BOOST_TEST(sources.file(program->rules[1].loc.file).path.find("b.meld") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(include_directories_are_searched_after_the_including_folder) {
  TempDir dir;
  dir.write("lib/robot.meld", "const top = 5.\n");
  dir.write("local/robot.meld", "const top = 6.\n");
  std::string main =
      dir.write("local/main.meld", "include #robot.meld\ntype linear a(node, int).\na(@0, top).\n");
  SourceManager sources;
  std::ostringstream err;
  Diagnostics diag(sources, err);
  auto program = loadProgram(main, {(dir.path / "lib").string()}, sources, diag);
  BOOST_REQUIRE(program);
  BOOST_TEST(toString(program->consts.at(0).value) == "6");
}

BOOST_AUTO_TEST_CASE(missing_include_and_cycle_are_errors_at_the_include) {
  TempDir dir;
  dir.write("x.meld", "include #y.meld\n");
  dir.write("y.meld", "include #x.meld\n");
  std::string main = dir.write("main.meld", "include #nope.meld\ninclude #x.meld\ntype a(node).\n");
  SourceManager sources;
  std::ostringstream err;
  Diagnostics diag(sources, err);
  auto program = loadProgram(main, {}, sources, diag);
  BOOST_TEST(diag.errorCount() == 2, err.str());
  BOOST_TEST(
      err.str().find("main.meld:1:1: error: cannot find included file 'nope.meld'") != std::string::npos,
      err.str());
  BOOST_TEST(err.str().find("y.meld:1:1: error: include cycle") != std::string::npos, err.str());
}

BOOST_AUTO_TEST_CASE(a_file_is_included_once) {
  TempDir dir;
  dir.write("common.meld", "type c(node).\n");
  dir.write("a.meld", "include #common.meld\n");
  std::string main = dir.write("main.meld", "include #a.meld\ninclude #common.meld\n");
  SourceManager sources;
  std::ostringstream err;
  Diagnostics diag(sources, err);
  auto program = loadProgram(main, {}, sources, diag);
  BOOST_REQUIRE(program);
  BOOST_TEST(program->predicates.size() == 1u);
}

BOOST_AUTO_TEST_CASE(front_end_applies_defines) {
  TempDir dir;
  std::string main = dir.write("main.meld", "type linear a(node, int).\nconst limit = 3.\na(@0, limit).\n");
  SourceManager sources;
  std::ostringstream err;
  Diagnostics diag(sources, err);
  FrontEndInput input{main, {}, {{"limit", "4 * 2"}, {"extra", "[1, 2]"}}};
  auto program = runFrontEnd(input, sources, diag);
  BOOST_REQUIRE_MESSAGE(program, err.str());
  BOOST_TEST(toString(program->consts.at(0).value) == "(4 * 2)");
  BOOST_TEST(program->consts.at(1).name == "extra");
  BOOST_TEST(program->consts.at(1).fromCommandLine);
}
