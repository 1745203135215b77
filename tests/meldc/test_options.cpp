#define BOOST_TEST_MODULE meldc_options
#include <boost/test/unit_test.hpp>

#include "meldc/options.hpp"

using namespace meldc;

BOOST_AUTO_TEST_CASE(all_options) {
  std::string error;
  auto o = parseOptions(
      {"prog.meld", "-o", "out.txt", "-I", "a", "-Ib", "-Dx=1", "-D", "y-z=@3", "--emit=ast"}, error);
  BOOST_REQUIRE_MESSAGE(o, error);
  BOOST_TEST(o->input == "prog.meld");
  BOOST_TEST(o->output == "out.txt");
  BOOST_TEST(o->includeDirs.size() == 2u);
  BOOST_TEST(o->includeDirs[1] == "b");
  BOOST_TEST(o->defines.size() == 2u);
  BOOST_TEST(o->defines[1].first == "y-z");
  BOOST_TEST(o->defines[1].second == "@3");
  BOOST_TEST((o->emit == EmitKind::Ast));
}

BOOST_AUTO_TEST_CASE(default_is_bytecode) {
  std::string error;
  auto o = parseOptions({"prog.meld"}, error);
  BOOST_REQUIRE(o);
  BOOST_TEST((o->emit == EmitKind::Bytecode));
  auto c = parseOptions({"--check", "prog.meld"}, error);
  BOOST_TEST((c->emit == EmitKind::Check));
  auto n = parseOptions({"prog.meld", "--emit=nodes"}, error);
  BOOST_REQUIRE(n);
  BOOST_TEST((n->emit == EmitKind::Nodes));
  auto l = parseOptions({"prog.meld", "--emit=llvm"}, error);
  BOOST_REQUIRE(l);
  BOOST_TEST((l->emit == EmitKind::Llvm));
}

BOOST_AUTO_TEST_CASE(usage_errors) {
  std::string error;
  BOOST_TEST(!parseOptions({}, error));
  BOOST_TEST(error == "no input file");
  BOOST_TEST(!parseOptions({"a.meld", "b.meld"}, error));
  BOOST_TEST(!parseOptions({"a.meld", "--emit=elf"}, error));
  BOOST_TEST(error == "unknown --emit kind 'elf' (expected ast, nodes, bytecode, native, asm or llvm)");
  BOOST_TEST(!parseOptions({"a.meld", "-DX=1"}, error));
  BOOST_TEST(!parseOptions({"a.meld", "-Dx"}, error));
  BOOST_TEST(!parseOptions({"a.meld", "-o"}, error));
  BOOST_TEST(error == "option '-o' needs a value");
  BOOST_TEST(parseOptions({"--help"}, error).has_value());
}

BOOST_AUTO_TEST_CASE(no_stdlib) {
  std::string error;
  auto o = parseOptions({"prog.meld"}, error);
  BOOST_REQUIRE(o);
  BOOST_TEST(!o->noStdlib);
  auto n = parseOptions({"prog.meld", "--no-stdlib", "-I", "a"}, error);
  BOOST_REQUIRE(n);
  BOOST_TEST(n->noStdlib);
  BOOST_TEST(n->includeDirs.size() == 1u);  // the driver, not the parser, appends the stdlib folder
}

BOOST_AUTO_TEST_CASE(jobs) {
  std::string error;
  auto d = parseOptions({"prog.meld"}, error);
  BOOST_REQUIRE(d);
  BOOST_TEST(d->jobs == 0u);  // one thread per processor
  for (const auto& [args, jobs] :
       std::vector<std::pair<std::vector<std::string>, unsigned>>{{{"prog.meld", "-j", "3"}, 3u},
                                                                  {{"-j12", "prog.meld"}, 12u},
                                                                  {{"prog.meld", "--jobs=9999"}, 9999u}}) {
    auto o = parseOptions(args, error);
    BOOST_REQUIRE_MESSAGE(o, error);
    BOOST_TEST(o->jobs == jobs);
    BOOST_TEST(o->input == "prog.meld");
  }
  for (const std::vector<std::string>& bad :
       std::vector<std::vector<std::string>>{{"prog.meld", "-j", "0"},
                                             {"prog.meld", "-j10000"},
                                             {"prog.meld", "--jobs=two"},
                                             {"prog.meld", "-j-1"}}) {
    BOOST_TEST(!parseOptions(bad, error));
    BOOST_TEST(error.find("needs a number of threads from 1 to 9999") != std::string::npos);
  }
  BOOST_TEST(!parseOptions({"prog.meld", "-j"}, error));
  BOOST_TEST(error == "option '-j' needs a value");
}
