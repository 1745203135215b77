// What the checks make of ground facts (ast/ground_fact.hpp).
//
// A ground fact stays compact only when the checks would pass it without a word: its predicate is
// declared once by the program (not a built-in, not imported, not an action), its home is a node
// literal for a `node` home, its mark agrees with the predicate, and every literal has the type of
// its field (int, float, node, string or bool; an int literal may fill a float field). Every other
// one becomes an ast::Rule at its place in the program, exactly as the parser would have built
// it, and meets the usual checks and messages.
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/source.hpp"

namespace meldc {

void admitGroundFacts(ast::Program& program, const SourceManager& sources);

// Every ground fact as an ast::Rule (for --emit=ast, which prints the whole AST).
void materializeGroundFacts(ast::Program& program, const SourceManager& sources);

// The statement the parser would have built for `fact`.
ast::Rule groundFactRule(const ast::GroundFacts& facts, const ast::GroundFact& fact,
                         const SourceManager& sources);

}  // namespace meldc
