// Small text helpers that several layers need.
#pragma once

#include <cctype>
#include <string_view>

namespace support {

// ASCII letters compared without case (names of targets, special predicates).
inline bool sameIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

}  // namespace support
