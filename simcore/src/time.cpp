#include "simcore/time.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace simcore {

std::optional<SimTime> parseDuration(std::string_view text) {
  if (text.empty()) return std::nullopt;
  const std::string s(text);
  char* end = nullptr;
  const double value = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || !std::isfinite(value) || value < 0) return std::nullopt;
  const std::string unit(end);
  double scale;
  if (unit.empty() || unit == "s")
    scale = 1e9;
  else if (unit == "ms")
    scale = 1e6;
  else if (unit == "us")
    scale = 1e3;
  else if (unit == "ns")
    scale = 1;
  else if (unit == "min")
    scale = 60e9;
  else if (unit == "h")
    scale = 3600e9;
  else
    return std::nullopt;
  const double ns = value * scale;
  if (ns >= 9.2e18) return std::nullopt;
  return SimTime(std::llround(ns));
}

std::string formatTime(SimTime t) {
  char buf[48];
  const char* sign = t < 0 ? "-" : "";
  const std::uint64_t a = t < 0 ? std::uint64_t(-(t + 1)) + 1 : std::uint64_t(t);
  std::snprintf(buf, sizeof buf, "%s%llu.%09llu s", sign, (unsigned long long)(a / 1000000000ull),
                (unsigned long long)(a % 1000000000ull));
  return buf;
}

}  // namespace simcore
