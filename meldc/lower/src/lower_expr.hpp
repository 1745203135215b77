// Lowering of expressions and conditions (§5.5) to register code: values go to registers,
// conditions (`&&`, `||`, `~`, comparisons) compile to branches with short-circuit.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include "code_builder.hpp"
#include "lower_context.hpp"

namespace meldc {

class ExprLowerer {
 public:
  using Label = CodeBuilder::Label;
  ExprLowerer(Lowering& L, CodeBuilder& cb) : L_(L), cb_(cb) {}

  // Variables in scope: name -> register. Callers save and restore it around scopes.
  std::map<std::string, Reg> env;

  // A register holding the value (possibly a variable's own register: never write to it).
  Reg value(const ast::Expr& e);
  // The value in a register of exactly type `want` (int literals in float places become floats).
  Reg valueAs(const ast::Expr& e, meldvm::TypeId want);
  // Computes the value into `dst`.
  void into(const ast::Expr& e, Reg dst);

  void jumpIfFalse(const ast::Expr& cond, Label target);
  void jumpIfTrue(const ast::Expr& cond, Label target);
  // A boolean-valued call used as a condition (`queens_violation(Y, L)` in a body).
  Reg call(ast::Symbol name, const std::vector<const ast::Expr*>& args, SourceLoc loc,
           meldvm::TypeId resultHint);
  Reg call(ast::Symbol name, const std::vector<ast::Expr>& args, SourceLoc loc, meldvm::TypeId resultHint);

  // A call with its arguments already in registers (custom aggregates).
  Reg callRegs(ast::Symbol name, const std::vector<Reg>& regs, SourceLoc loc, meldvm::TypeId resultHint);

  Reg folded(const Folded& f, meldvm::TypeId want);
  // Compares register `r` with the expression: jumps to `fail` when they differ.
  void testEqual(Reg r, const ast::Expr& e, Label fail);

  // Free variables of an expression (not `let` locals).
  static void variables(const ast::Expr& e, std::set<std::string>& out);
  bool bound(const ast::Expr& e) const;

 private:
  Reg arithmetic(const ast::Expr& e);
  std::optional<Reg> foldedArithmetic(const ast::Expr& e);  // nothing unless it folds
  Reg compareValue(const ast::Expr& e);
  Reg list(const ast::Expr& e);
  // Emits a comparison whose truth is `sense` -> jump.
  void compareJump(const ast::Expr& e, Label target, bool jumpWhen);

  Lowering& L_;
  CodeBuilder& cb_;
};

}  // namespace meldc
