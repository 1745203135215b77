// Parsing one source file (or one expression) into the AST, with lexical and syntax errors
// reported as diagnostics. Includes are listed in Program::includes but not followed here
// (that is the job of the include pass, includes.hpp).
#pragma once

#include <cstdint>
#include <optional>

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"

namespace meldc {

// Returns nullopt when the file has lexical or syntax errors (all of them are reported).
// Errors found while building the AST (bad aggregate shape, section order, ...) are reported too;
// the returned program is then incomplete but well-formed.
// With `groundFacts`, the facts of literals only are read by a fast scanner into
// Program::groundFacts instead of into rules (ast/ground_fact.hpp).
std::optional<ast::Program> parseFile(uint32_t file, const SourceManager& sources, Diagnostics& diag,
                                      bool groundFacts = false);

// Parses the whole text of `file` as one expression (used for -DNAME=VALUE).
std::optional<ast::Expr> parseExpression(uint32_t file, const SourceManager& sources, Diagnostics& diag);

}  // namespace meldc
