#include "meldc/parser.hpp"

#include <sstream>

#include "MeldLexer.h"
#include "MeldParser.h"
#include "antlr4-runtime.h"
#include "ast_builder.hpp"
#include "ground_scan.hpp"
#include "syntax_errors.hpp"

namespace meldc {

namespace {

using meldgen::MeldLexer;
using meldgen::MeldParser;

// Everything one parse needs, in destruction-safe order.
struct ParseSession {
  // `text`: the file's text, or what is left of it once its ground facts are taken out.
  ParseSession(uint32_t file, const std::string& text, Diagnostics& diag)
      : input(text),
        lexer(&input),
        tokens(&lexer),
        parser(&tokens),
        lexErrors(diag, file),
        strategy(std::make_shared<MeldErrorStrategy>(diag, file)) {
    lexer.removeErrorListeners();
    lexer.addErrorListener(&lexErrors);
    parser.removeErrorListeners();
    parser.addErrorListener(&lexErrors);
    parser.setErrorHandler(strategy);
  }

  // Reports the tokens the lexer sets aside: stray characters (warning, skipped like cl-meld
  // does), unterminated strings and comments (errors). Returns false on errors.
  bool checkTokens(uint32_t file, Diagnostics& diag) {
    tokens.fill();
    bool ok = lexErrors.errors() == 0;
    for (antlr4::Token* t : tokens.getTokens()) {
      SourceLoc loc{file, static_cast<uint32_t>(t->getLine()),
                    static_cast<uint32_t>(t->getCharPositionInLine()) + 1};
      switch (t->getType()) {
        case MeldLexer::STRAY:
          diag.warning(loc, "ignoring stray character '" + t->getText() + "'");
          break;
        case MeldLexer::BAD_STRING:
          diag.error(loc, "unterminated string (a string ends with '\"' on the same line)");
          ok = false;
          break;
        case MeldLexer::UNTERMINATED_COMMENT:
          diag.error(loc, "unterminated comment: '/*' without '*/'");
          ok = false;
          break;
        default:
          break;
      }
    }
    return ok;
  }

  bool syntaxOk() const { return strategy->errors() == 0 && lexErrors.errors() == 0; }

  antlr4::ANTLRInputStream input;
  MeldLexer lexer;
  antlr4::CommonTokenStream tokens;
  MeldParser parser;
  DiagnosticsListener lexErrors;
  std::shared_ptr<MeldErrorStrategy> strategy;
};

// The ANTLR input stream throws on malformed UTF-8: report the first bad byte instead.
bool validUtf8(uint32_t file, const SourceManager& sources, Diagnostics& diag) {
  const std::string& text = sources.file(file).text;
  uint32_t line = 1, col = 1;
  for (size_t i = 0; i < text.size();) {
    // Strict UTF-8 (RFC 3629): no overlong forms, no surrogates, nothing past U+10FFFF — the
    // lexer's converter throws on those.
    unsigned char c = static_cast<unsigned char>(text[i]);
    size_t len = c < 0x80                   ? 1
                 : (c >= 0xC2 && c <= 0xDF) ? 2
                 : (c >= 0xE0 && c <= 0xEF) ? 3
                 : (c >= 0xF0 && c <= 0xF4) ? 4
                                            : 0;
    bool ok = len != 0 && i + len <= text.size();
    if (ok && len > 1) {
      const unsigned char second = static_cast<unsigned char>(text[i + 1]);
      const unsigned char low = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
      const unsigned char high = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
      ok = second >= low && second <= high;
    }
    for (size_t k = 2; ok && k < len; ++k) ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (!ok) {
      diag.error(SourceLoc{file, line, col}, "the file is not valid UTF-8 text (bad byte here)");
      return false;
    }
    if (c == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
    i += len;
  }
  return true;
}

// A file without syntax errors or stray characters, parsed one top-level item at a time: the
// parse tree of each item is freed once its AST is built, instead of the whole file's tree living
// until the end (a generated file of millions of axioms took about 2 KB of parse tree per axiom).
// Returns nothing when the file has a syntax error or a lexer diagnostic; the whole-file parse then
// reports them as before (the messages of this pass are dropped).
// With `scan`, ANTLR reads the text without the ground facts, and the facts join the program
// between the items they stand between.
std::optional<ast::Program> parseItemByItem(uint32_t file, const SourceManager& sources, Diagnostics& diag,
                                            GroundScan* scan) {
  std::ostringstream dropped;
  Diagnostics syntax(sources, dropped);
  ParseSession session(file, scan ? scan->rest : sources.file(file).text, syntax);
  if (!session.checkTokens(file, syntax) || syntax.warningCount() != 0) return std::nullopt;
  std::ostringstream astText;  // the AST builder's diagnostics, kept if the whole file parses
  Diagnostics astDiag(sources, astText);
  AstBuilder builder(astDiag, file);
  ast::Program program;
  std::vector<ast::GroundFact> noFacts;
  std::vector<ast::GroundFact>& facts = scan ? scan->facts.facts : noFacts;
  std::size_t nextFact = 0;
  auto placeFactsBefore = [&](uint32_t line, uint32_t col) {
    const std::size_t first = nextFact;
    for (; nextFact < facts.size(); ++nextFact) {
      const SourceLoc& at = facts[nextFact].loc;
      if (at.line > line || (at.line == line && at.col > col)) break;
      facts[nextFact].position = static_cast<uint32_t>(program.rules.size());
    }
    if (nextFact > first) builder.noteStatement();  // for the order of sections (§2.1)
  };
  while (session.tokens.LA(1) != antlr4::Token::EOF) {
    MeldParser::TopItemContext* item = session.parser.topItem();
    if (!session.syntaxOk()) return std::nullopt;
    placeFactsBefore(static_cast<uint32_t>(item->getStart()->getLine()),
                     static_cast<uint32_t>(item->getStart()->getCharPositionInLine()) + 1);
    builder.addTopItem(item, program);
    session.parser.getTreeTracker().reset();  // every context of the item (the parser holds none)
  }
  placeFactsBefore(UINT32_MAX, UINT32_MAX);
  if (scan) program.groundFacts = std::move(scan->facts);
  diag.append(astDiag, astText.str());
  return program;
}

}  // namespace

std::optional<ast::Program> parseFile(uint32_t file, const SourceManager& sources, Diagnostics& diag,
                                      bool groundFacts) {
  if (!validUtf8(file, sources, diag)) return std::nullopt;
  std::optional<GroundScan> scan =
      groundFacts ? scanGroundFacts(sources.file(file).text, file) : std::nullopt;
  if (std::optional<ast::Program> program = parseItemByItem(file, sources, diag, scan ? &*scan : nullptr))
    return program;
  // A syntax error: the whole original text again, so that every message is the usual one.
  ParseSession session(file, sources.file(file).text, diag);
  if (!session.checkTokens(file, diag)) return std::nullopt;
  MeldParser::ProgramContext* tree = session.parser.program();
  if (!session.syntaxOk()) return std::nullopt;
  AstBuilder builder(diag, file);
  return builder.buildProgram(tree);
}

std::optional<ast::Expr> parseExpression(uint32_t file, const SourceManager& sources, Diagnostics& diag) {
  if (!validUtf8(file, sources, diag)) return std::nullopt;
  ParseSession session(file, sources.file(file).text, diag);
  if (!session.checkTokens(file, diag)) return std::nullopt;
  MeldParser::StandaloneExprContext* tree = session.parser.standaloneExpr();
  if (!session.syntaxOk()) return std::nullopt;
  AstBuilder builder(diag, file);
  return builder.buildExpr(tree->expr());
}

}  // namespace meldc
