// A whole program: the declarations and statements of the main file and of its includes,
// merged in the order of §4.8 (main file first, then included files in reverse order).
#pragma once

#include <string>
#include <vector>

#include "meldc/ast/decl.hpp"
#include "meldc/ast/rule.hpp"

namespace meldc::ast {

struct IncludeDecl {  // include #path
  SourceLoc loc;
  std::string path;  // as written, blanks and a trailing // comment removed
};

struct Program {
  std::vector<IncludeDecl> includes;
  std::vector<NodeTypeDecl> nodeTypes;
  std::vector<TypeAliasDecl> typeAliases;
  std::vector<PredicateDecl> predicates;
  std::vector<ExportDecl> exports;
  std::vector<Directive> directives;
  std::vector<ExternDecl> externs;
  std::vector<ConstDecl> consts;
  std::vector<FunDecl> funs;
  std::vector<Rule> rules;  // rules and facts in source order

  // Appends everything of `other` after the items already here.
  void append(Program&& other);
};

}  // namespace meldc::ast
