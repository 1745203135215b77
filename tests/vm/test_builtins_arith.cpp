#define BOOST_TEST_MODULE vm_builtins_arith
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "meldvm/arith.hpp"
#include "meldvm/value_ops.hpp"

using namespace meldvm;

namespace {
constexpr std::int32_t kMin = std::numeric_limits<std::int32_t>::min();
constexpr std::int32_t kMax = std::numeric_limits<std::int32_t>::max();
std::string fmt(double d) {
  std::string s;
  appendFloat(s, d);
  return s;
}
}  // namespace

BOOST_AUTO_TEST_CASE(integer_division_truncates_toward_zero) {
  BOOST_CHECK_EQUAL(intDiv(7, 2), 3);
  BOOST_CHECK_EQUAL(intDiv(-7, 2), -3);
  BOOST_CHECK_EQUAL(intDiv(7, -2), -3);
  BOOST_CHECK_EQUAL(intDiv(-7, -2), 3);
  BOOST_CHECK_EQUAL(intDiv(6, 3), 2);
  BOOST_CHECK_EQUAL(intDiv(0, -5), 0);
  BOOST_CHECK_EQUAL(intDiv(kMin, -1), kMin);  // wraps instead of trapping
  BOOST_CHECK_EQUAL(intDiv(kMin, 1), kMin);
}

BOOST_AUTO_TEST_CASE(modulo_has_the_sign_of_the_dividend) {
  BOOST_CHECK_EQUAL(intMod(7, 3), 1);
  BOOST_CHECK_EQUAL(intMod(-7, 3), -1);
  BOOST_CHECK_EQUAL(intMod(7, -3), 1);
  BOOST_CHECK_EQUAL(intMod(-7, -3), -1);
  BOOST_CHECK_EQUAL(intMod(9, 8), 1);
  BOOST_CHECK_EQUAL(intMod(-8, 8), 0);
  BOOST_CHECK_EQUAL(intMod(kMin, -1), 0);
}

BOOST_AUTO_TEST_CASE(division_and_modulo_by_zero_are_runtime_errors) {
  BOOST_CHECK_THROW(intDiv(1, 0), RuntimeError);
  BOOST_CHECK_THROW(intDiv(0, 0), RuntimeError);
  BOOST_CHECK_THROW(intMod(5, 0), RuntimeError);
  try {
    intDiv(3, 0);
    BOOST_FAIL("no error");
  } catch (const RuntimeError& e) {
    BOOST_CHECK_EQUAL(std::string(e.what()), "integer division by zero");
  }
}

BOOST_AUTO_TEST_CASE(add_sub_mul_wrap_around_at_32_bits) {
  BOOST_CHECK_EQUAL(intAdd(2, 3), 5);
  BOOST_CHECK_EQUAL(intAdd(kMax, 1), kMin);
  BOOST_CHECK_EQUAL(intSub(kMin, 1), kMax);
  BOOST_CHECK_EQUAL(intSub(3, 5), -2);
  BOOST_CHECK_EQUAL(intMul(-4, 6), -24);
  BOOST_CHECK_EQUAL(intMul(65536, 65536), 0);
  BOOST_CHECK_EQUAL(intMul(65536, 32768), kMin);
  BOOST_CHECK_EQUAL(intMul(kMax, 2), -2);
}

BOOST_AUTO_TEST_CASE(int_to_float_is_exact_and_float_to_int_truncates) {
  BOOST_CHECK_EQUAL(intToFloat(-3), -3.0);
  BOOST_CHECK_EQUAL(intToFloat(kMax), 2147483647.0);
  BOOST_CHECK_EQUAL(fmt(intToFloat(2)), "2");
  BOOST_CHECK_EQUAL(fmt(intToFloat(123456)), "1.2346e+05");
  BOOST_CHECK_EQUAL(floatToInt(2.9), 2);
  BOOST_CHECK_EQUAL(floatToInt(-2.9), -2);
  BOOST_CHECK_EQUAL(floatToInt(0.5), 0);
  BOOST_CHECK_EQUAL(floatToInt(-0.5), 0);
  BOOST_CHECK_EQUAL(floatToInt(1e10), kMax);
  BOOST_CHECK_EQUAL(floatToInt(-1e10), kMin);
  BOOST_CHECK_EQUAL(floatToInt(std::nan("")), 0);
}

BOOST_AUTO_TEST_CASE(float_arithmetic_is_ieee) {
  BOOST_CHECK_EQUAL(fmt(7.0 / 2.0), "3.5");
  BOOST_CHECK_EQUAL(fmt(1.0 / 0.0), "inf");
  BOOST_CHECK_EQUAL(fmt(-1.0 / 0.0), "-inf");
  BOOST_CHECK_EQUAL(fmt(1.0 / 3.0), "0.33333");
}

BOOST_AUTO_TEST_CASE(comparisons) {
  BOOST_CHECK(compareInts(CmpOp::Lt, -1, 0));
  BOOST_CHECK(!compareInts(CmpOp::Lt, 0, 0));
  BOOST_CHECK(compareInts(CmpOp::Le, 0, 0));
  BOOST_CHECK(compareInts(CmpOp::Gt, 5, -5));
  BOOST_CHECK(!compareInts(CmpOp::Ge, -6, -5));
  BOOST_CHECK(compareInts(CmpOp::Eq, 4, 4));
  BOOST_CHECK(compareInts(CmpOp::Ne, 4, 5));
  BOOST_CHECK(!compareInts(CmpOp::Ne, 4, 4));
  BOOST_CHECK(compareFloats(CmpOp::Lt, 1.5, 2.0));
  BOOST_CHECK(compareFloats(CmpOp::Eq, 0.0, -0.0));
  BOOST_CHECK(compareFloats(CmpOp::Ge, 2.0, 2.0));
  const double nan = std::nan("");
  BOOST_CHECK(!compareFloats(CmpOp::Eq, nan, nan));
  BOOST_CHECK(compareFloats(CmpOp::Ne, nan, nan));
  BOOST_CHECK(!compareFloats(CmpOp::Lt, nan, 1.0));
  BOOST_CHECK(!compareFloats(CmpOp::Ge, nan, 1.0));
}
