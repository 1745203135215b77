// Turns ANTLR's recognition errors into house diagnostics with readable messages
// ("unexpected name 'b', expected ',' or '.'") instead of ANTLR's token dumps.
#pragma once

#include <cstdint>

#include "antlr4-runtime.h"
#include "meldc/diagnostics.hpp"

namespace meldc {

class MeldErrorStrategy : public antlr4::DefaultErrorStrategy {
 public:
  MeldErrorStrategy(Diagnostics& diag, uint32_t file) : diag_(diag), file_(file) {}
  int errors() const { return errors_; }

 protected:
  void reportNoViableAlternative(antlr4::Parser* parser, const antlr4::NoViableAltException& e) override;
  void reportInputMismatch(antlr4::Parser* parser, const antlr4::InputMismatchException& e) override;
  void reportFailedPredicate(antlr4::Parser* parser, const antlr4::FailedPredicateException& e) override;
  void reportUnwantedToken(antlr4::Parser* parser) override;
  void reportMissingToken(antlr4::Parser* parser) override;

 private:
  void emit(SourceLoc loc, const std::string& message);
  SourceLoc at(antlr4::Token* token) const;

  Diagnostics& diag_;
  uint32_t file_;
  int errors_ = 0;
  SourceLoc last_;
};

// Anything ANTLR would print on the console (lexer errors) goes to the diagnostics instead.
class DiagnosticsListener : public antlr4::BaseErrorListener {
 public:
  DiagnosticsListener(Diagnostics& diag, uint32_t file) : diag_(diag), file_(file) {}
  void syntaxError(antlr4::Recognizer* recognizer, antlr4::Token* offendingSymbol, size_t line,
                   size_t charPositionInLine, const std::string& msg, std::exception_ptr e) override;
  int errors() const { return errors_; }

 private:
  Diagnostics& diag_;
  uint32_t file_;
  int errors_ = 0;
};

}  // namespace meldc
