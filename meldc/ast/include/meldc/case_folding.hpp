// Meld names compare case-insensitively (language reference §1.3). The front end folds every name
// of the AST once into a Symbol (ast/symbol.hpp); these are for the places before that (include
// merging, -D definitions) and for keywords in messages.
#pragma once

#include <cctype>
#include <string>
#include <string_view>

#include "support/text.hpp"

namespace meldc {

inline std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

inline bool sameName(std::string_view a, std::string_view b) { return support::sameIgnoringCase(a, b); }

}  // namespace meldc
