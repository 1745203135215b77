// A readable dump of the AST (`meldc --emit=ast`): one line per declaration, rules as indented
// trees of their body and head items, expressions fully parenthesised, locations as [line:col].
#pragma once

#include <ostream>
#include <string>

#include "meldc/ast/program.hpp"
#include "meldc/source.hpp"

namespace meldc {

std::string toString(const ast::Expr& e);
std::string toString(const ast::TypeExpr& t);
std::string toString(const ast::Term& t);  // one line, nested items included
void dumpProgram(const ast::Program& program, const SourceManager& sources, std::ostream& out);

}  // namespace meldc
