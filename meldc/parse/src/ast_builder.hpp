// Builds the AST of one file from its ANTLR parse tree (a visitor over the generated contexts).
// Also reports the errors that the grammar leaves to it: the section order of §2.1, heads written
// with a number other than 1, aggregate shapes outside §2.2, unknown aggregate modifiers, integer
// literals out of range, and empty include names.
#pragma once

#include <cstdint>

#include "MeldBaseVisitor.h"
#include "MeldParser.h"
#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

class AstBuilder : public meldgen::MeldBaseVisitor {
 public:
  AstBuilder(Diagnostics& diag, uint32_t file) : diag_(diag), file_(file) {}

  ast::Program buildProgram(meldgen::MeldParser::ProgramContext* ctx);
  // One top-level item at a time, into `program` (the file parsed item by item).
  void addTopItem(meldgen::MeldParser::TopItemContext* ctx, ast::Program& program) { topItem(ctx, program); }
  ast::Expr buildExpr(meldgen::MeldParser::ExprContext* ctx);
  // A statement that the parser read without ANTLR (a ground fact) stands here: items of earlier
  // sections after it are out of order.
  void noteStatement();

  // Expressions and conditions.
  antlrcpp::Any visitMulExpr(meldgen::MeldParser::MulExprContext* ctx) override;
  antlrcpp::Any visitAddExpr(meldgen::MeldParser::AddExprContext* ctx) override;
  antlrcpp::Any visitPrimaryExpr(meldgen::MeldParser::PrimaryExprContext* ctx) override;
  antlrcpp::Any visitVarExpr(meldgen::MeldParser::VarExprContext* ctx) override;
  antlrcpp::Any visitAnonExpr(meldgen::MeldParser::AnonExprContext* ctx) override;
  antlrcpp::Any visitArgExpr(meldgen::MeldParser::ArgExprContext* ctx) override;
  antlrcpp::Any visitTrueExpr(meldgen::MeldParser::TrueExprContext* ctx) override;
  antlrcpp::Any visitFalseExpr(meldgen::MeldParser::FalseExprContext* ctx) override;
  antlrcpp::Any visitStringExpr(meldgen::MeldParser::StringExprContext* ctx) override;
  antlrcpp::Any visitIntExpr(meldgen::MeldParser::IntExprContext* ctx) override;
  antlrcpp::Any visitFloatExpr(meldgen::MeldParser::FloatExprContext* ctx) override;
  antlrcpp::Any visitCallExpr(meldgen::MeldParser::CallExprContext* ctx) override;
  antlrcpp::Any visitConstExpr(meldgen::MeldParser::ConstExprContext* ctx) override;
  antlrcpp::Any visitNodeExpr(meldgen::MeldParser::NodeExprContext* ctx) override;
  antlrcpp::Any visitSpecialExpr(meldgen::MeldParser::SpecialExprContext* ctx) override;
  antlrcpp::Any visitParenExpr(meldgen::MeldParser::ParenExprContext* ctx) override;
  antlrcpp::Any visitStructExpr(meldgen::MeldParser::StructExprContext* ctx) override;
  antlrcpp::Any visitConvExpr(meldgen::MeldParser::ConvExprContext* ctx) override;
  antlrcpp::Any visitIfExpr(meldgen::MeldParser::IfExprContext* ctx) override;
  antlrcpp::Any visitLetExpr(meldgen::MeldParser::LetExprContext* ctx) override;
  antlrcpp::Any visitNilExpr(meldgen::MeldParser::NilExprContext* ctx) override;
  antlrcpp::Any visitListExpr(meldgen::MeldParser::ListExprContext* ctx) override;
  antlrcpp::Any visitNotCond(meldgen::MeldParser::NotCondContext* ctx) override;
  antlrcpp::Any visitAndCond(meldgen::MeldParser::AndCondContext* ctx) override;
  antlrcpp::Any visitOrCond(meldgen::MeldParser::OrCondContext* ctx) override;
  antlrcpp::Any visitCompareCond(meldgen::MeldParser::CompareCondContext* ctx) override;
  antlrcpp::Any visitInCond(meldgen::MeldParser::InCondContext* ctx) override;
  antlrcpp::Any visitParenCond(meldgen::MeldParser::ParenCondContext* ctx) override;
  antlrcpp::Any visitCallCond(meldgen::MeldParser::CallCondContext* ctx) override;

  // Terms of bodies and heads.
  antlrcpp::Any visitSubgoalTerm(meldgen::MeldParser::SubgoalTermContext* ctx) override;
  antlrcpp::Any visitExistsTerm(meldgen::MeldParser::ExistsTermContext* ctx) override;
  antlrcpp::Any visitComprehensionTerm(meldgen::MeldParser::ComprehensionTermContext* ctx) override;
  antlrcpp::Any visitAggregateTerm(meldgen::MeldParser::AggregateTermContext* ctx) override;
  antlrcpp::Any visitConditionalTerm(meldgen::MeldParser::ConditionalTermContext* ctx) override;
  antlrcpp::Any visitCondTerm(meldgen::MeldParser::CondTermContext* ctx) override;

 private:
  SourceLoc loc(antlr4::Token* token) const;
  SourceLoc loc(antlr4::ParserRuleContext* ctx) const { return loc(ctx->getStart()); }

  ast::Expr expr(meldgen::MeldParser::ExprContext* ctx);
  ast::Expr cond(meldgen::MeldParser::CondContext* ctx);
  ast::Expr primary(meldgen::MeldParser::PrimaryContext* ctx);
  std::vector<ast::Expr> args(meldgen::MeldParser::ArgsContext* ctx);
  std::vector<ast::Term> terms(meldgen::MeldParser::TermsContext* ctx);
  std::vector<ast::Term> head(meldgen::MeldParser::HeadContext* ctx);
  std::vector<ast::VarDecl> varList(meldgen::MeldParser::VarListContext* ctx);
  ast::TypeExpr type(meldgen::MeldParser::TypeExprContext* ctx);
  std::vector<ast::FieldDecl> fields(meldgen::MeldParser::FieldDeclsContext* ctx);
  double number(meldgen::MeldParser::NumberContext* ctx);
  ast::Expr binary(ast::ExprKind kind, ast::BinOp op, antlr4::Token* at, ast::Expr lhs, ast::Expr rhs);
  void delay(ast::Term& t, antlr4::tree::TerminalNode* d);
  int64_t intLiteral(antlr4::Token* token, bool negative, int64_t min, int64_t max, const char* what);

  void topItem(meldgen::MeldParser::TopItemContext* ctx, ast::Program& program);
  void definition(meldgen::MeldParser::DefinitionContext* ctx, ast::Program& program);
  void directive(meldgen::MeldParser::DirectiveContext* ctx, ast::Program& program);
  ast::Rule statement(meldgen::MeldParser::StatementContext* ctx);

  Diagnostics& diag_;
  uint32_t file_;
  int section_ = 0;  // highest section seen so far (§2.1)
};

}  // namespace meldc
