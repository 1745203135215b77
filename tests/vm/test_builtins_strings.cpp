#define BOOST_TEST_MODULE vm_builtins_strings
#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "builtins_fixture.hpp"

using namespace bitest;

BOOST_FIXTURE_TEST_SUITE(strings, Fix)

BOOST_AUTO_TEST_CASE(concatenate_values) {
  BOOST_CHECK_EQUAL(show("concatenate", {str("ab"), str("cd")}, tString), "\"abcd\"");
  BOOST_CHECK_EQUAL(show("concatenate", {str(""), str("x")}, tString), "\"x\"");
  BOOST_CHECK_EQUAL(show("concatenate", {str(""), str("")}, tString), "\"\"");
}

BOOST_AUTO_TEST_CASE(str2float_str2int_like_atof_atoi) {
  BOOST_CHECK_EQUAL(call("str2float", {str("3.5")}, tFloat).asFloat(), 3.5);
  BOOST_CHECK_EQUAL(call("str2float", {str("-0.25")}, tFloat).asFloat(), -0.25);
  BOOST_CHECK_EQUAL(call("str2float", {str(" 2.5x")}, tFloat).asFloat(), 2.5);
  BOOST_CHECK_EQUAL(call("str2float", {str("abc")}, tFloat).asFloat(), 0.0);
  BOOST_CHECK_EQUAL(call("str2float", {str("")}, tFloat).asFloat(), 0.0);
  BOOST_CHECK_EQUAL(call("str2int", {str("42")}, tInt).asInt(), 42);
  BOOST_CHECK_EQUAL(call("str2int", {str("-17")}, tInt).asInt(), -17);
  BOOST_CHECK_EQUAL(call("str2int", {str("  12abc")}, tInt).asInt(), 12);
  BOOST_CHECK_EQUAL(call("str2int", {str("abc")}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("str2int", {str("")}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("str2int", {str("4294967297")}, tInt).asInt(), 1);  // wraps at 32 bits
}

BOOST_AUTO_TEST_CASE(int2str_float2str) {
  BOOST_CHECK_EQUAL(show("int2str", {I(-45)}, tString), "\"-45\"");
  BOOST_CHECK_EQUAL(show("int2str", {I(0)}, tString), "\"0\"");
  BOOST_CHECK_EQUAL(show("int2str", {I(-2147483647 - 1)}, tString), "\"-2147483648\"");
  BOOST_CHECK_EQUAL(show("float2str", {F(3.14159)}, tString), "\"3.141590\"");
  BOOST_CHECK_EQUAL(show("float2str", {F(-0.5)}, tString), "\"-0.500000\"");
  BOOST_CHECK_EQUAL(show("float2str", {F(2)}, tString), "\"2.000000\"");
  BOOST_CHECK_EQUAL(show("float2str", {F(1e20)}, tString), "\"100000000000000000000.000000\"");
  BOOST_CHECK_EQUAL(show("float2str", {F(1e-7)}, tString), "\"0.000000\"");
}

BOOST_AUTO_TEST_CASE(str2intlist_fields) {
  BOOST_CHECK_EQUAL(show("str2intlist", {str("1,2,3")}, tLI), "[1,2,3]");
  BOOST_CHECK_EQUAL(show("str2intlist", {str("")}, tLI), "[]");
  BOOST_CHECK_EQUAL(show("str2intlist", {str("5")}, tLI), "[5]");
  BOOST_CHECK_EQUAL(show("str2intlist", {str("1,,2")}, tLI), "[1,0,2]");
  BOOST_CHECK_EQUAL(show("str2intlist", {str("1,2,")}, tLI), "[1,2]");
  BOOST_CHECK_EQUAL(show("str2intlist", {str(" 4, -5")}, tLI), "[4,-5]");
}

BOOST_AUTO_TEST_CASE(filecountwords_counts_words) {
  const std::string path = std::string(MELD_BINARY_DIR) + "/vm_builtins_words.txt";
  {
    std::ofstream out(path);
    out << "hello world\n  foo\tbar\n\n";
  }
  BOOST_CHECK_EQUAL(call("filecountwords", {str(path), I(0)}, tInt).asInt(), 4);
  { std::ofstream out(path); }
  BOOST_CHECK_EQUAL(call("filecountwords", {str(path), I(1)}, tInt).asInt(), 0);
  std::remove(path.c_str());
  BOOST_CHECK_THROW(call("filecountwords", {str(path), I(0)}, tInt), RuntimeError);
}

BOOST_AUTO_TEST_SUITE_END()
