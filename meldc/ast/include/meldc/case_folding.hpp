// Meld names compare case-insensitively (language reference §1.3): every pass folds with this.
#pragma once

#include <cctype>
#include <string>
#include <string_view>

namespace meldc {

inline std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace meldc
