// Arithmetic and comparison semantics of spec §5.5 / §3.2, as the interpreter applies them:
// int is 32-bit two's complement with wrap-around on overflow, `/` truncates toward zero and `%`
// takes the sign of the dividend (C semantics), float is IEEE double, int→float is exact
// (`float(N)`), float→int truncates (`float2int`). Division or modulo of ints by zero has no
// defined result in the spec (the established VM dies of SIGFPE); here it raises RuntimeError.
// INT_MIN / -1 wraps to INT_MIN and INT_MIN % -1 is 0 (what wrap-around arithmetic gives).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace meldvm {

// A run-time error the spec defines (out-of-range index, empty list, division by zero, ...).
// The message names the operation, e.g. "lnth: index 3 out of range for a list of 2 elements".
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr std::int32_t intAdd(std::int32_t a, std::int32_t b) {
  return std::int32_t(std::uint32_t(a) + std::uint32_t(b));
}
constexpr std::int32_t intSub(std::int32_t a, std::int32_t b) {
  return std::int32_t(std::uint32_t(a) - std::uint32_t(b));
}
constexpr std::int32_t intMul(std::int32_t a, std::int32_t b) {
  return std::int32_t(std::uint32_t(a) * std::uint32_t(b));
}
inline std::int32_t intDiv(std::int32_t a, std::int32_t b) {
  if (b == 0) throw RuntimeError("integer division by zero");
  if (b == -1) return intSub(0, a);  // INT_MIN / -1 wraps
  return a / b;
}
inline std::int32_t intMod(std::int32_t a, std::int32_t b) {
  if (b == 0) throw RuntimeError("integer modulo by zero");
  if (b == -1) return 0;
  return a % b;
}

constexpr double intToFloat(std::int32_t i) { return double(i); }

// C cast semantics for in-range values (truncation toward zero). Out of range and NaN are UB in C;
// here they saturate to INT_MIN/INT_MAX and NaN gives 0, so the result is always defined.
inline std::int32_t floatToInt(double d) {
  if (std::isnan(d)) return 0;
  if (d >= 2147483647.0) return std::numeric_limits<std::int32_t>::max();
  if (d <= -2147483648.0) return std::numeric_limits<std::int32_t>::min();
  return std::int32_t(d);
}

enum class CmpOp : std::uint8_t { Eq, Ne, Lt, Le, Gt, Ge };

template <class T>
constexpr bool compareScalars(CmpOp op, T a, T b) {
  switch (op) {
    case CmpOp::Eq:
      return a == b;
    case CmpOp::Ne:
      return a != b;
    case CmpOp::Lt:
      return a < b;
    case CmpOp::Le:
      return a <= b;
    case CmpOp::Gt:
      return a > b;
    case CmpOp::Ge:
      return a >= b;
  }
  return false;
}
// Floats compare as C doubles: any comparison with NaN is false except `<>`.
constexpr bool compareInts(CmpOp op, std::int32_t a, std::int32_t b) { return compareScalars(op, a, b); }
constexpr bool compareFloats(CmpOp op, double a, double b) { return compareScalars(op, a, b); }

}  // namespace meldvm
