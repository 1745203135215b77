// The parser's fast lane for data: finds the ground facts of a file (`[!]name(@N, lit, ...).`
// written as one top-level statement, ast/ground_fact.hpp) without ANTLR, and blanks them out of
// the text that ANTLR then reads.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "meldc/ast/ground_fact.hpp"

namespace meldc {

struct GroundScan {
  ast::GroundFacts facts;  // in file order; positions are set when the parser merges them
  // The text without those facts: every other token keeps its line and column (a line left with
  // blanks only becomes empty), so ANTLR's positions stay those of the file.
  std::string rest;
};

// Nothing when the file has no ground fact, or a character or construct the scanner does not
// follow exactly as the ANTLR lexer would (a stray character, an unterminated string or comment):
// ANTLR then reads the whole text as it is.
std::optional<GroundScan> scanGroundFacts(std::string_view text, std::uint32_t file);

}  // namespace meldc
