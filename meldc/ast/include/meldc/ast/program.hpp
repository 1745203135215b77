// A whole program: the declarations and statements of the main file and of its includes,
// merged in the order of §4.8 (main file first, then included files in reverse order).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meldc/ast/decl.hpp"
#include "meldc/ast/ground_fact.hpp"
#include "meldc/ast/rule.hpp"

namespace meldc::ast {

struct IncludeDecl {  // include #path
  SourceLoc loc;
  std::string path;              // as written, blanks and a trailing // comment removed
  std::optional<uint32_t> file;  // the SourceManager file it loaded (unset: skipped or failed)
};

// One node of the initial node set after renumbering (§6.1): internal id, id in the source.
struct NodeId {
  int64_t internal = 0;
  int64_t source = 0;
  friend bool operator==(const NodeId&, const NodeId&) = default;
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
  // Facts of literals only, kept compact (ground_fact.hpp); each knows its place among `rules`.
  GroundFacts groundFacts;
  // Every name of the program folded once (symbol.hpp); filled by internNames.
  SymbolTable symbols;

  uint32_t mainFile = 0;  // SourceManager index of the main file (set by include merging)
  // Set by node renumbering (renumber.hpp): the initial nodes ordered by internal id. Node
  // literals in the AST hold internal ids from then on.
  bool renumbered = false;
  std::vector<NodeId> nodeTable;

  // Appends everything of `other` after the items already here (not mainFile / nodeTable).
  void append(Program&& other);
};

// Visits the statements in program order: the rules, and each ground fact just before the rule it
// stands before. `P` is Program or const Program.
template <class P, class OnRule, class OnFact>
void forEachStatement(P& program, OnRule onRule, OnFact onFact) {
  auto& facts = program.groundFacts.facts;
  std::size_t next = 0;
  for (std::size_t i = 0; i <= program.rules.size(); ++i) {
    for (; next < facts.size() && facts[next].position <= i; ++next) onFact(facts[next]);
    if (i < program.rules.size()) onRule(program.rules[i]);
  }
}

}  // namespace meldc::ast
