#include "syntax_errors.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "MeldLexer.h"
#include "MeldParser.h"
#include "meldc/case_folding.hpp"

namespace meldc {

namespace {

using meldgen::MeldLexer;

using Vocab = antlr4::dfa::Vocabulary;

std::string symbolic(const Vocab& v, size_t type) { return std::string(v.getSymbolicName(type)); }

bool isKeyword(const Vocab& v, size_t type) { return symbolic(v, type).rfind("K_", 0) == 0; }

std::string shorten(const std::string& text) { return text.size() > 40 ? text.substr(0, 37) + "..." : text; }

// How an offending token is shown in a message.
std::string describe(const Vocab& v, antlr4::Token* token) {
  if (!token || token->getType() == antlr4::Token::EOF) return "end of file";
  size_t type = token->getType();
  std::string text = shorten(token->getText());
  switch (type) {
    case MeldLexer::IDENT:
    case MeldLexer::QIDENT:
      return "name '" + text + "'";
    case MeldLexer::VARIABLE:
      return "variable '" + text + "'";
    case MeldLexer::INT:
    case MeldLexer::FLOAT:
      return "number '" + text + "'";
    case MeldLexer::STRING:
      return "string " + text;
    case MeldLexer::FILE:
      return "file name '" + text + "'";
    case MeldLexer::DELAY:
      return "delay '" + text + "'";
    default:
      break;
  }
  if (isKeyword(v, type)) return "keyword '" + text + "'";
  return "'" + text + "'";
}

// How an expected token type is shown in a message.
std::string expectedName(const Vocab& v, size_t type) {
  switch (type) {
    case antlr4::Token::EOF:
      return "end of file";
    case MeldLexer::IDENT:
      return "a name";
    case MeldLexer::VARIABLE:
      return "a variable";
    case MeldLexer::INT:
    case MeldLexer::FLOAT:
      return "a number";
    case MeldLexer::STRING:
      return "a string";
    case MeldLexer::FILE:
      return "a file name (#path)";
    case MeldLexer::DELAY:
      return "a delay";
    case MeldLexer::ARG:
      return "@argN";
    default:
      break;
  }
  if (isKeyword(v, type)) {
    std::string quoted = "'";  // appended: GCC 12 -O3 warns (-Wrestrict) on "'" + std::string&&
    quoted += lower(symbolic(v, type).substr(2));
    quoted += '\'';
    return quoted;
  }
  std::string literal(v.getLiteralName(type));
  if (!literal.empty()) return literal;
  return symbolic(v, type);
}

// "expected A", "expected A or B", "expected A, B or C"; empty when the set is too large to help.
std::string expectedList(const Vocab& v, const antlr4::misc::IntervalSet& set) {
  std::vector<size_t> types;
  for (ssize_t t : set.toList()) types.push_back(static_cast<size_t>(t));
  bool hasName = std::find(types.begin(), types.end(), MeldLexer::IDENT) != types.end();
  std::vector<std::string> names;
  for (size_t t : types) {
    if (hasName && (t == MeldLexer::QIDENT || t == MeldLexer::K_INDEX || t == MeldLexer::K_COMPACT ||
                    t == MeldLexer::K_DATA || t == MeldLexer::K_PRIORITY || t == MeldLexer::K_ALLOCATOR))
      continue;
    std::string n = expectedName(v, t);
    if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  }
  if (names.empty() || names.size() > 5) return "";
  std::string out = "expected ";
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += names[i];
  }
  return out;
}

// Extra advice for mistakes that are common when coming from other languages.
std::string hint(antlr4::Parser* parser, antlr4::Token* token) {
  if (!token) return "";
  switch (token->getType()) {
    case MeldLexer::BANG_EQ:
      return "; Meld writes 'not equal' as '<>'";
    case MeldLexer::EQ_EQ:
      return "; Meld compares with a single '='";
    case MeldLexer::LT:
    case MeldLexer::LE:
    case MeldLexer::GT:
    case MeldLexer::GE:
    case MeldLexer::EQ:
    case MeldLexer::NE:
      return "; comparisons cannot be chained, write 'A < B, B < C'";
    default:
      break;
  }
  auto* stream = parser->getTokenStream();
  size_t index = token->getTokenIndex();
  if (index > 0) {
    antlr4::Token* prev = stream->get(index - 1);
    for (size_t i = index - 1; prev->getChannel() != antlr4::Token::DEFAULT_CHANNEL && i > 0;)
      prev = stream->get(--i);
    if (prev->getType() == MeldLexer::MINUS &&
        (token->getType() == MeldLexer::VARIABLE || token->getType() == MeldLexer::LPAREN))
      return "; Meld has no unary minus, write '0 - X' or '-1 * X'";
  }
  return "";
}

}  // namespace

SourceLoc MeldErrorStrategy::at(antlr4::Token* token) const {
  SourceLoc loc;
  loc.file = file_;
  loc.line = static_cast<uint32_t>(token->getLine());
  loc.col = static_cast<uint32_t>(token->getCharPositionInLine()) + 1;
  return loc;
}

void MeldErrorStrategy::emit(SourceLoc loc, const std::string& message) {
  if (errors_ > 0 && loc == last_) return;  // one message per position
  last_ = loc;
  ++errors_;
  diag_.error(loc, message);
}

void MeldErrorStrategy::reportNoViableAlternative(antlr4::Parser* parser,
                                                  const antlr4::NoViableAltException& e) {
  antlr4::Token* token = e.getOffendingToken();
  emit(at(token), "unexpected " + describe(parser->getVocabulary(), token) + hint(parser, token));
}

void MeldErrorStrategy::reportInputMismatch(antlr4::Parser* parser, const antlr4::InputMismatchException& e) {
  antlr4::Token* token = e.getOffendingToken();
  std::string expected = expectedList(parser->getVocabulary(), e.getExpectedTokens());
  emit(at(token), "unexpected " + describe(parser->getVocabulary(), token) +
                      (expected.empty() ? "" : ", " + expected) + hint(parser, token));
}

void MeldErrorStrategy::reportFailedPredicate(antlr4::Parser* parser,
                                              const antlr4::FailedPredicateException& e) {
  antlr4::Token* token = e.getOffendingToken();
  emit(at(token), "unexpected " + describe(parser->getVocabulary(), token));
}

void MeldErrorStrategy::reportUnwantedToken(antlr4::Parser* parser) {
  if (inErrorRecoveryMode(parser)) return;
  beginErrorCondition(parser);
  antlr4::Token* token = parser->getCurrentToken();
  std::string expected = expectedList(parser->getVocabulary(), getExpectedTokens(parser));
  emit(at(token), "unexpected " + describe(parser->getVocabulary(), token) +
                      (expected.empty() ? "" : ", " + expected) + hint(parser, token));
}

void MeldErrorStrategy::reportMissingToken(antlr4::Parser* parser) {
  if (inErrorRecoveryMode(parser)) return;
  beginErrorCondition(parser);
  antlr4::Token* token = parser->getCurrentToken();
  std::string expected = expectedList(parser->getVocabulary(), getExpectedTokens(parser));
  if (expected.empty()) expected = "more input";
  // Point just after the previous token: that is where the missing token belongs.
  SourceLoc loc = at(token);
  antlr4::Token* prev = parser->getTokenStream()->LT(-1);
  if (prev && prev->getType() != antlr4::Token::EOF) {
    loc = at(prev);
    std::string text = prev->getText();
    if (text.find('\n') == std::string::npos) loc.col += static_cast<uint32_t>(text.size());
  }
  emit(loc, expected + " before " + describe(parser->getVocabulary(), token));
}

void DiagnosticsListener::syntaxError(antlr4::Recognizer*, antlr4::Token*, size_t line,
                                      size_t charPositionInLine, const std::string& msg, std::exception_ptr) {
  ++errors_;
  SourceLoc loc;
  loc.file = file_;
  loc.line = static_cast<uint32_t>(line);
  loc.col = static_cast<uint32_t>(charPositionInLine) + 1;
  diag_.error(loc, msg);
}

}  // namespace meldc
