// Ground facts: statements `[!]name(@N, literal, ...).` whose arguments are all literals.
//
// Generated programs hold them by the hundred thousand (edges of a graph, initial values). They
// are data, not code: the parser takes them out before ANTLR sees the file and keeps them here in
// a few dozen bytes each, instead of a parse tree and Term/Expr objects (kilobytes each). The
// checks admit those whose predicate, mark and literal types are plainly right
// (ground_facts.hpp); every other one becomes an ordinary ast::Rule again, so that it meets the
// usual checks and diagnostics. Admitted facts go from here to the axiom blocks of their nodes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meldc/ast/term.hpp"
#include "meldc/source.hpp"

namespace meldc::ast {

struct GroundArg {
  enum class Kind : std::uint8_t { Int, Float, Node, String, Bool };
  Kind kind = Kind::Int;
  std::uint16_t length = 0;  // of the literal's text in the source (with its '-', '@' or quotes)
  std::uint32_t line = 0;    // 1-based line and column of that text
  std::uint32_t col = 0;
  std::uint32_t offset = 0;  // byte offset of that text in the source file
  // Int: the value; Node: the node id (internal after renumbering); Bool: 0 or 1. Float: the
  // literal read in single precision and widened (§1.4), as the lowering of literals does.
  union {
    std::int64_t i = 0;
    double f;
  };
};

struct GroundFact {
  std::uint32_t name = 0;      // index into GroundFacts::names
  std::uint32_t firstArg = 0;  // index into GroundFacts::args
  std::uint16_t argCount = 0;
  bool persistentMark = false;  // written with '!'
  SourceLoc loc;                // of the statement (its '!' or its name)
  std::uint32_t nameCol = 0;    // the name is on the line of `loc`
  // The fact stands before Program::rules[position] in program order (after all rules when
  // position == rules.size()).
  std::uint32_t position = 0;
};

struct GroundFacts {
  std::vector<std::string> names;  // predicate names as written
  std::vector<Symbol> nameSyms;    // their symbols (internNames), once interned
  std::vector<GroundFact> facts;   // in program order
  std::vector<GroundArg> args;

  bool empty() const { return facts.empty(); }
  const std::string& name(const GroundFact& f) const { return names[f.name]; }
  const GroundArg& arg(const GroundFact& f, std::size_t i) const { return args[f.firstArg + i]; }
  // Appends `other` (whose positions count from `rulesBefore`, the rules already in the program).
  void append(GroundFacts&& other, std::uint32_t rulesBefore);
};

}  // namespace meldc::ast
