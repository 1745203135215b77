#include "ground_scan.hpp"

#include <array>
#include <charconv>
#include <climits>
#include <cstdlib>
#include <unordered_map>
#include <utility>
#include <vector>

namespace meldc {

namespace {

// Just enough of the lexer of Meld.g4 to know where top-level statements end: the places where a
// '.' is no DOT token (comments, strings, include paths, float literals, identifiers that swallow
// digits) and the tokens of a ground fact. Anything it cannot follow exactly makes it give up.
enum class Tok {
  End,
  Bad,
  Ident,
  Variable,
  Int,
  Float,
  String,
  AtInt,
  Dot,
  LParen,
  RParen,
  Open,
  Close,
  Comma,
  Bang,
  Minus,
  File,
  Other
};

struct Token {
  Tok kind = Tok::End;
  std::size_t begin = 0, end = 0;
  std::uint32_t line = 0, col = 0;
  bool spaceBefore = false, commentBefore = false;
};

bool isLower(char c) { return c >= 'a' && c <= 'z'; }
bool isUpper(char c) { return c >= 'A' && c <= 'Z'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlnum(char c) { return isLower(c) || isUpper(c) || isDigit(c); }
bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f'; }

class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {}

  Token next() {
    Token t;
    if (!skipBlanksAndComments(t)) return t;  // t.kind is Bad
    t.begin = pos_;
    t.line = line_;
    t.col = col_;
    if (pos_ >= text_.size()) {
      t.end = pos_;
      return t;  // End
    }
    t.kind = scanToken();
    t.end = pos_;
    return t;
  }

  std::string_view text(const Token& t) const { return text_.substr(t.begin, t.end - t.begin); }

 private:
  char at(std::size_t i) const { return i < text_.size() ? text_[i] : '\0'; }

  void advanceTo(std::size_t end) {
    for (; pos_ < end; ++pos_) {
      const unsigned char c = static_cast<unsigned char>(text_[pos_]);
      if (c == '\n') {
        ++line_;
        col_ = 1;
      } else if ((c & 0xC0) != 0x80) {  // columns count code points, as ANTLR's do
        ++col_;
      }
    }
  }

  bool skipBlanksAndComments(Token& t) {
    for (;;) {
      const char c = at(pos_);
      if (pos_ < text_.size() && isBlank(c)) {
        advanceTo(pos_ + 1);
        t.spaceBefore = true;
      } else if (c == '/' && at(pos_ + 1) == '/') {
        std::size_t eol = text_.find('\n', pos_);
        advanceTo(eol == std::string_view::npos ? text_.size() : eol);
        t.commentBefore = true;
      } else if (c == '/' && at(pos_ + 1) == '*') {
        std::size_t close = text_.find("*/", pos_ + 2);
        if (close == std::string_view::npos) {
          t.kind = Tok::Bad;  // unterminated comment
          return false;
        }
        advanceTo(close + 2);
        t.commentBefore = true;
      } else {
        return true;
      }
    }
  }

  template <class Pred>
  void skipWhile(std::size_t from, Pred pred) {
    std::size_t end = from;
    while (end < text_.size() && pred(text_[end])) ++end;
    advanceTo(end);
  }

  Tok scanToken() {
    const char c = text_[pos_];
    const char n = at(pos_ + 1);
    if (isLower(c)) {
      skipWhile(pos_ + 1, [](char x) { return isAlnum(x) || x == '_' || x == '?' || x == '-'; });
      return Tok::Ident;
    }
    if (isUpper(c)) {
      skipWhile(pos_ + 1, [](char x) { return isAlnum(x) || x == '_'; });
      return Tok::Variable;
    }
    if (isDigit(c)) {
      skipWhile(pos_, isDigit);
      if (at(pos_) != '.' || !isDigit(at(pos_ + 1))) return Tok::Int;
      skipWhile(pos_ + 1, isDigit);
      return Tok::Float;
    }
    switch (c) {
      case '"': {
        std::size_t end = text_.find_first_of("\"\r\n", pos_ + 1);
        if (end == std::string_view::npos || text_[end] != '"') return Tok::Bad;  // unterminated
        advanceTo(end + 1);
        return Tok::String;
      }
      case '#': {
        std::size_t eol = text_.find_first_of("\r\n", pos_);
        advanceTo(eol == std::string_view::npos ? text_.size() : eol);
        return Tok::File;
      }
      case '\'':
        if (!isAlnum(n) && n != '_') return Tok::Bad;  // a lone quote is a stray character
        skipWhile(pos_ + 1, [](char x) { return isAlnum(x) || x == '_'; });
        return Tok::Other;
      case '@':
        if (isDigit(n)) {
          skipWhile(pos_ + 1, isDigit);
          return Tok::AtInt;
        }
        skipWhile(pos_ + 1, [](char x) { return isAlnum(x) || x == '_' || x == '+'; });
        return Tok::Other;
      case '&':
        if (n != '&') return Tok::Bad;
        advanceTo(pos_ + 2);
        return Tok::Other;
      case ':':
        advanceTo(pos_ + (n == '(' || n == '-' ? 2 : 1));
        return n == '(' ? Tok::Open : Tok::Other;
      case '-':
        advanceTo(pos_ + (n == 'o' ? 2 : 1));  // '-o'
        return n == 'o' ? Tok::Other : Tok::Minus;
      case '!':
        advanceTo(pos_ + (n == '=' ? 2 : 1));
        return n == '=' ? Tok::Other : Tok::Bang;
      default:
        break;
    }
    advanceTo(pos_ + 1);
    switch (c) {
      case '.':
        return Tok::Dot;
      case '(':
        return Tok::LParen;
      case ')':
        return Tok::RParen;
      case '[':
      case '{':
        return Tok::Open;
      case ']':
      case '}':
        return Tok::Close;
      case ',':
        return Tok::Comma;
      case '=':
      case '<':
      case '>':
      case '~':
      case '?':
      case '$':
      case '|':
      case '+':
      case '*':
      case '%':
      case '/':
      case '_':
        return Tok::Other;
      default:
        return Tok::Bad;  // a character no token starts with (ANTLR warns and skips it)
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::uint32_t line_ = 1, col_ = 1;
};

// Keywords are lower case in their first letter and of any case after it (Meld.g4).
bool sameWord(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i)
    if ((isUpper(word[i]) ? char(word[i] + 32) : word[i]) != keyword[i]) return false;
  return true;
}

bool keyword(std::string_view word) {
  static constexpr std::array<std::string_view, 41> kKeywords = {
      "type",      "exists",   "extern", "const",   "bool",      "int",    "float", "node",   "thread",
      "string",    "list",     "set",    "array",   "include",   "random", "route", "action", "linear",
      "export",    "import",   "custom", "from",    "as",        "let",    "ins",   "in",     "end",
      "if",        "then",     "fun",    "else",    "otherwise", "min",    "true",  "false",  "nil",
      "allocator", "priority", "index",  "compact", "data"};
  for (std::string_view k : kKeywords)
    if (sameWord(word, k)) return true;
  return false;
}

// Reads the facts of one file; `lx` is left after the fact's '.' when one matches.
class FactReader {
 public:
  FactReader(std::string_view text, std::uint32_t file, ast::GroundFacts& out)
      : text_(text), file_(file), out_(out) {}

  // On a match, `end` is the byte after the fact's '.'.
  bool read(Lexer& lx, const Token& first, std::size_t& end) {
    Lexer start = lx;
    const std::size_t argsBefore = out_.args.size();
    if (readFact(lx, first, end)) return true;
    lx = start;
    out_.args.resize(argsBefore);
    return false;
  }

 private:
  // The next token, when no comment stands before it (a comment inside a fact keeps it in ANTLR's
  // text: blanking it could shift the columns of what follows).
  static bool nextPlain(Lexer& lx, Token& t) {
    t = lx.next();
    return !t.commentBefore;
  }

  bool readFact(Lexer& lx, Token t, std::size_t& end) {
    ast::GroundFact fact;
    fact.loc = SourceLoc{file_, t.line, t.col};
    if (t.kind == Tok::Bang) {
      fact.persistentMark = true;
      if (!nextPlain(lx, t)) return false;
    }
    if (t.kind != Tok::Ident || t.line != fact.loc.line || keyword(lx.text(t))) return false;
    fact.nameCol = t.col;
    const std::string_view name = lx.text(t);
    if (!nextPlain(lx, t) || t.kind != Tok::LParen) return false;
    fact.firstArg = static_cast<std::uint32_t>(out_.args.size());
    do {
      if (!nextPlain(lx, t) || !literal(lx, t)) return false;
      if (!nextPlain(lx, t)) return false;
    } while (t.kind == Tok::Comma);
    if (t.kind != Tok::RParen || !nextPlain(lx, t) || t.kind != Tok::Dot) return false;
    const std::size_t count = out_.args.size() - fact.firstArg;
    if (count > UINT16_MAX) return false;
    fact.argCount = static_cast<std::uint16_t>(count);
    fact.name = intern(name);
    out_.facts.push_back(fact);
    end = t.end;
    return true;
  }

  bool literal(Lexer& lx, Token t) {
    ast::GroundArg arg;
    arg.line = t.line;
    arg.col = t.col;
    const std::size_t begin = t.begin;
    bool negative = false;
    if (t.kind == Tok::Minus) {
      negative = true;
      t = lx.next();
      if (t.spaceBefore || t.commentBefore || (t.kind != Tok::Int && t.kind != Tok::Float)) return false;
    }
    const std::string_view spelling = text_.substr(begin, t.end - begin);
    switch (t.kind) {
      case Tok::Int:
      case Tok::AtInt: {
        const std::string_view digits = lx.text(t).substr(t.kind == Tok::AtInt ? 1 : 0);
        std::int64_t value = 0;
        auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec != std::errc() || ptr != digits.data() + digits.size() ||
            value > INT32_MAX + std::int64_t(negative))
          return false;  // out of range: the AST builder reports it
        arg.kind = t.kind == Tok::AtInt ? ast::GroundArg::Kind::Node : ast::GroundArg::Kind::Int;
        arg.i = negative ? -value : value;
        break;
      }
      case Tok::Float: {
        if (spelling.size() > 64) return false;
        char buf[65];
        spelling.copy(buf, spelling.size());
        buf[spelling.size()] = '\0';
        arg.kind = ast::GroundArg::Kind::Float;
        arg.f = double(std::strtof(buf, nullptr));
        break;
      }
      case Tok::String:
        arg.kind = ast::GroundArg::Kind::String;
        break;
      case Tok::Ident: {
        const bool isTrue = sameWord(lx.text(t), "true");
        if (!isTrue && !sameWord(lx.text(t), "false")) return false;
        arg.kind = ast::GroundArg::Kind::Bool;
        arg.i = isTrue ? 1 : 0;
        break;
      }
      default:
        return false;
    }
    if (spelling.size() > UINT16_MAX) return false;
    arg.offset = static_cast<std::uint32_t>(begin);
    arg.length = static_cast<std::uint16_t>(spelling.size());
    out_.args.push_back(arg);
    return true;
  }

  std::uint32_t intern(std::string_view name) {
    auto it = names_.find(name);
    if (it != names_.end()) return it->second;
    const auto id = static_cast<std::uint32_t>(out_.names.size());
    out_.names.emplace_back(name);
    names_.emplace(name, id);  // the view points into `text_`, which outlives this reader
    return id;
  }

  std::string_view text_;
  std::uint32_t file_;
  ast::GroundFacts& out_;
  std::unordered_map<std::string_view, std::uint32_t> names_;
};

// The text with the facts' bytes blanked (newlines kept); a line that held a fact and nothing but
// blanks otherwise is left empty, so ANTLR skips one newline instead of the fact's width.
std::string blankOut(std::string_view text, const std::vector<std::pair<std::size_t, std::size_t>>& ranges) {
  std::string rest;
  rest.reserve(text.size() / 8);
  std::string line;
  std::size_t r = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t eol = text.find('\n', start);
    const std::size_t end = eol == std::string_view::npos ? text.size() : eol;
    line.clear();
    bool touched = false, blank = true;
    for (std::size_t i = start; i < end; ++i) {
      while (r < ranges.size() && ranges[r].second <= i) ++r;
      char c = text[i];
      if (r < ranges.size() && ranges[r].first <= i) {
        c = ' ';
        touched = true;
      }
      blank = blank && isBlank(c);
      line += c;
    }
    if (!(touched && blank)) rest += line;
    if (eol == std::string_view::npos) break;
    rest += '\n';
    start = eol + 1;
  }
  return rest;
}

}  // namespace

std::optional<GroundScan> scanGroundFacts(std::string_view text, std::uint32_t file) {
  GroundScan scan;
  FactReader reader(text, file, scan.facts);
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  Lexer lx(text);
  bool boundary = true;  // the next token starts a top-level item
  int depth = 0, existsDepth = -1;
  for (;;) {
    const Token t = lx.next();
    if (t.kind == Tok::Bad) return std::nullopt;
    if (t.kind == Tok::End) break;
    if (boundary && (t.kind == Tok::Bang || t.kind == Tok::Ident)) {
      std::size_t end = 0;
      if (reader.read(lx, t, end)) {
        ranges.emplace_back(t.begin, end);
        continue;
      }
    }
    boundary = false;
    switch (t.kind) {
      case Tok::LParen:
      case Tok::Open:
        ++depth;
        break;
      case Tok::RParen:
      case Tok::Close:
        depth = depth > 0 ? depth - 1 : 0;
        break;
      case Tok::Ident:
        if (existsDepth < 0 && sameWord(lx.text(t), "exists"))
          existsDepth = depth;  // `exists X.`: that '.' ends no statement
        break;
      case Tok::Dot:
        if (existsDepth == depth)
          existsDepth = -1;
        else if (depth == 0)
          boundary = true;
        break;
      case Tok::File:
        boundary = true;  // an include has no '.'
        break;
      default:
        break;
    }
  }
  if (scan.facts.empty()) return std::nullopt;
  scan.rest = blankOut(text, ranges);
  return scan;
}

}  // namespace meldc
