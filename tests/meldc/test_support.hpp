// Helpers for the meldc unit tests: parse a program from a string, collect the diagnostics.
#pragma once

#include <optional>
#include <sstream>
#include <string>

#include "meldc/ast/program.hpp"
#include "meldc/ast/symbol.hpp"
#include "meldc/ast_dump.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/names.hpp"
#include "meldc/parser.hpp"
#include "meldc/source.hpp"

struct Parsed {
  meldc::SourceManager sources;
  std::ostringstream messages;
  meldc::Diagnostics diag{sources, messages};
  std::optional<meldc::ast::Program> program;

  explicit Parsed(const std::string& text, bool names = false) {
    uint32_t file = sources.add("t.meld", text);
    program = meldc::parseFile(file, sources, diag);
    if (program) meldc::ast::internNames(*program);  // as the front end does before the checks
    if (program && names && !diag.hasErrors()) meldc::resolveNames(*program, diag);
  }
  bool ok() const { return program.has_value() && !diag.hasErrors(); }
  std::string errors() const { return messages.str(); }
  const meldc::ast::Rule& rule(size_t i) const { return program->rules.at(i); }
};

// The one-line form of the i-th head (or body) item of rule r.
inline std::string headItem(const Parsed& p, size_t r, size_t i) {
  return meldc::toString(p.rule(r).head.at(i));
}
inline std::string bodyItem(const Parsed& p, size_t r, size_t i) {
  return meldc::toString(p.rule(r).body.at(i));
}
