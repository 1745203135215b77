// Simulated time: a signed 64-bit count of nanoseconds, and parsing of user-written durations.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace simcore {

using SimTime = std::int64_t;  // nanoseconds

inline constexpr SimTime kNanosecond = 1;
inline constexpr SimTime kMicrosecond = 1000;
inline constexpr SimTime kMillisecond = 1000 * kMicrosecond;
inline constexpr SimTime kSecond = 1000 * kMillisecond;
inline constexpr SimTime kTimeInfinity = INT64_MAX;

// Parses "1.5s", "250ms", "10us", "42ns", "3min" or a bare number of seconds ("2.5").
// Returns nullopt on anything else (negative, garbage, overflow).
std::optional<SimTime> parseDuration(std::string_view text);

// "1.250000000 s" style rendering with nanosecond precision, trailing zeros kept short.
std::string formatTime(SimTime t);

}  // namespace simcore
