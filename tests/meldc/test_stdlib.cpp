// The standard library include files (stdlib/) and the default include folder of the drivers:
// each target file passes the front end when included without -I, and declares the sensing and
// action predicates with exactly the shapes of docs/meld-language.md §7 (the runtime writes their
// fields by position) and the face constants of its target.
#define BOOST_TEST_MODULE meldc_stdlib
#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <sstream>

#include "meldc/ast_dump.hpp"
#include "meldc/frontend.hpp"
#include "meldc/includes.hpp"
#include "temp_dir.hpp"

using namespace meldc;

namespace {

// Runs the front end on a program including `target`.meld from the default folder; returns the
// AST dump ("" on errors, which are reported).
std::string frontEndDump(const std::string& target) {
  ::unsetenv("MELD_STDLIB");  // the built-in folder (the tree's stdlib/)
  TempDir dir;
  std::string main = dir.write("main.meld", "include #" + target +
                                                ".meld\ntype linear a(node).\na(X).\n"
                                                "a(X), !neighbor(X, Y, F) -o !setColor2(X, F).\n");
  SourceManager sources;
  std::ostringstream err;
  Diagnostics diag(sources, err);
  FrontEndInput input{main, {defaultStdlibDir()}, {}};
  auto program = runFrontEnd(input, sources, diag);
  BOOST_TEST(err.str().empty(), err.str());
  if (!program) return "";
  std::ostringstream out;
  dumpProgram(*program, sources, out);
  return out.str();
}

void expectLines(const std::string& dump, const std::vector<std::string>& lines) {
  for (const std::string& line : lines)
    BOOST_TEST(dump.find("\n" + line + " [") != std::string::npos, "missing '" << line << "' in\n" << dump);
}

void expectNoLine(const std::string& dump, const std::string& prefix) {
  BOOST_TEST(dump.find("\n" + prefix) == std::string::npos, "unexpected '" << prefix << "' in\n" << dump);
}

const std::vector<std::string> kCommon = {
    "type route neighbor(node, node, int)", "type vacant(node, int)", "type neighborCount(node, int)",
    "type at(node, int, int, int)",         "type linear tap(node)",  "type linear action terminate(node)"};

}  // namespace

BOOST_AUTO_TEST_CASE(default_folder_is_the_source_tree_stdlib_unless_overridden) {
  ::unsetenv("MELD_STDLIB");
  BOOST_TEST(defaultStdlibDir() == std::string(MELD_SOURCE_DIR) + "/stdlib");
  ::setenv("MELD_STDLIB", "/elsewhere", 1);
  BOOST_TEST(defaultStdlibDir() == "/elsewhere");
  ::setenv("MELD_STDLIB", "", 1);
  BOOST_TEST(defaultStdlibDir().empty());  // an empty value turns the folder off
  ::unsetenv("MELD_STDLIB");
}

BOOST_AUTO_TEST_CASE(blinkyblocks) {
  std::string dump = frontEndDump("blinkyblocks");
  expectLines(dump, kCommon);
  expectLines(dump,
              {"type linear accel(node, int)", "type linear shake(node, int, int, int)", "const bottom = 0",
               "const back = 1", "const right = 2", "const front = 3", "const left = 4", "const top = 5"});
  expectNoLine(dump, "type linear action moveTo");  // no motion
}

BOOST_AUTO_TEST_CASE(smartblocks) {
  std::string dump = frontEndDump("smartblocks");
  expectLines(dump, kCommon);
  expectLines(dump, {"type linear action moveTo(node, int, int, int)", "const north = 0", "const east = 1",
                     "const south = 2", "const west = 3", "type mobileOver(node, int)",
                     "type linear action senseMobile(node)", "type linear mobileAt(node, int, float, float, int)",
                     "type linear action airJet(node, int, float, int)"});
  expectNoLine(dump, "type linear accel");
}

BOOST_AUTO_TEST_CASE(catoms2d) {
  std::string dump = frontEndDump("catoms2d");
  expectLines(dump, kCommon);
  expectLines(dump,
              {"type linear action moveTo(node, int, int, int)", "const right = 0", "const top-right = 1",
               "const top-left = 2", "const left = 3", "const bottom-left = 4", "const bottom-right = 5"});
}

BOOST_AUTO_TEST_CASE(catoms3d) {
  std::string dump = frontEndDump("catoms3d");
  expectLines(dump, kCommon);
  expectLines(dump, {"const side0 = 0", "const side1 = 1", "const top2 = 2", "const top3 = 3",
                     "const top4 = 4", "const top5 = 5", "const side6 = 6", "const side7 = 7",
                     "const bottom8 = 8", "const bottom9 = 9", "const bottom10 = 10", "const bottom11 = 11"});
  expectLines(dump, {"type linear action moveTo(node, int, int, int)"});
}
