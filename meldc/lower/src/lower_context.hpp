// State shared by the lowering passes (lower*.cpp): the program being built, the name tables
// (predicates, functions, externs, constants) and the inferred types of the checked AST.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "code_builder.hpp"
#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"
#include "meldc/types.hpp"
#include "meldvm/program.hpp"

namespace meldc {

// A construct the back end cannot compile (or an internal inconsistency): reported as an error at
// `loc`; the statement is skipped and no program is produced.
struct LowerError : std::runtime_error {
  LowerError(SourceLoc l, const std::string& message) : std::runtime_error(message), loc(l) {}
  SourceLoc loc;
};

// Instruction predicates (§4.1.3, §5.7): no facts, each head occurrence is one opcode.
enum class Instruction {
  None,
  SetPriority,
  AddPriority,
  RemovePriority,
  SetDefaultPriority,
  ScheduleNext,
  SetStatic,
  SetMoving,
  SetAffinity,
  SetCpu,
  StopProgram
};

struct PredInfo {
  meldvm::PredId id = meldvm::Program::kNoPred;  // kNoPred for instructions
  Instruction instruction = Instruction::None;
  const ast::PredicateDecl* decl = nullptr;  // null for built-ins
};

// A `const` folded at compile time (§4.6).
struct Folded {
  enum Kind { Int, Float, Bool, String, Node } kind = Int;
  std::int64_t i = 0;
  double f = 0.0;
  bool b = false;
  std::string s;
};

// Float literals are read in single precision and widened (§1.4).
inline double floatLiteral(const ast::Expr& e) {
  return e.text.empty() ? double(float(e.floatValue)) : double(std::strtof(e.text.c_str(), nullptr));
}

struct Lowering {
  Lowering(const ast::Program& a, SourceManager& s, Diagnostics& d, meldvm::Program& p)
      : ast(a), sources(s), diag(d), prog(p) {}

  const ast::Program& ast;
  SourceManager& sources;
  Diagnostics& diag;
  meldvm::Program& prog;
  Typing typing;

  std::unordered_map<ast::Symbol, PredInfo> preds;
  std::unordered_map<ast::Symbol, Folded> folded;            // folded constants
  std::unordered_map<ast::Symbol, std::uint32_t> globals;    // constants computed at start-up: global id
  std::unordered_map<ast::Symbol, std::uint32_t> functions;  // user functions: function id
  std::unordered_map<ast::Symbol, std::uint32_t> externs;    // user externs: extern id
  std::map<std::string, std::uint32_t> strings;              // string constant -> index
  // The program has thread predicates (§6.12): `_init_thread` exists and rule 1 initialises the
  // thread node, so user rules start at 2 (§6.4.1).
  bool threads = false;

  const PredInfo* pred(ast::Symbol name) const;
  const PredInfo* builtinPred(std::string_view name) const;  // `_init`, `_init_thread`
  const meldvm::PredicateDesc& desc(const PredInfo& p) const { return prog.predicates[p.id]; }
  meldvm::TypeId vmType(const ast::TypeExpr& t);
  meldvm::TypeId typeOf(const ast::Expr& e);  // inferred type of an expression
  std::uint32_t string(const std::string& s);
  // The first line of the statement's text, for code block labels.
  std::string label(SourceLoc loc) const;
  // Marks the instructions `cb` emits from now on as coming from `loc` (derivation trees).
  void at(CodeBuilder& cb, SourceLoc loc);
  std::unordered_map<std::uint32_t, std::uint32_t> sourceFileIndex;  // SourceManager file -> program's
};

// lower_predicates.cpp: types, predicates, nodes, scheduling, indexes, externs (no code).
void lowerDeclarations(Lowering& L);
// lower_globals.cpp: constant folding, globals and their initialiser, user functions.
void lowerConstantsAndFunctions(Lowering& L);
std::optional<Folded> foldConstant(Lowering& L, const ast::Expr& e);
// lower_rule.cpp: user rules (numbered rules and persistent processes).
void lowerRules(Lowering& L);
// lower_axioms.cpp: rule 0, rule 1 (thread axioms, with thread predicates) and the per-node
// axiom blocks.
void lowerAxioms(Lowering& L);

bool isAxiom(const Lowering& L, const ast::Rule& r);  // a statement without body facts (§5.1)

}  // namespace meldc
