#include "meld_highlighter.hpp"

namespace ide {

namespace {

enum BlockState { kNormal = -1, kInComment = 1 };

QTextCharFormat makeFormat(const QColor& color, bool bold = false, bool italic = false) {
  QTextCharFormat f;
  f.setForeground(color);
  if (bold) f.setFontWeight(QFont::Bold);
  f.setFontItalic(italic);
  return f;
}

}  // namespace

MeldHighlighter::MeldHighlighter(QTextDocument* document) : QSyntaxHighlighter(document) {
  formats_[int(Role::Keyword)] = makeFormat(QColor(0x1f, 0x3f, 0xa8), true);
  formats_[int(Role::Type)] = makeFormat(QColor(0x00, 0x7a, 0x7a), true);
  formats_[int(Role::Predicate)] = makeFormat(QColor(0x8a, 0x2b, 0x8a));
  formats_[int(Role::Variable)] = makeFormat(QColor(0xa0, 0x5a, 0x00));
  formats_[int(Role::Number)] = makeFormat(QColor(0x0b, 0x7a, 0x26));
  formats_[int(Role::String)] = makeFormat(QColor(0xb0, 0x30, 0x30));
  formats_[int(Role::Node)] = makeFormat(QColor(0x0b, 0x7a, 0x26), true);
  formats_[int(Role::Comment)] = makeFormat(QColor(0x70, 0x70, 0x70), false, true);
  const auto ci = QRegularExpression::CaseInsensitiveOption;
  // Later rules win where they overlap (a string's content is not a keyword).
  rules_ = {
      {QRegularExpression(
           R"(\b(type|exists|extern|const|include|random|route|action|linear|export|import|custom|)"
           R"(from|as|let|ins|in|end|if|then|fun|else|otherwise|true|false|nil|allocator|)"
           R"(priority|index|compact|data|min|max|sum|count|first|collect)\b)",
           ci),
       Role::Keyword},
      {QRegularExpression(R"(\b(bool|int|float|node|thread|string|list|set|array)\b)", ci), Role::Type},
      {QRegularExpression(R"(!?\b[a-z][A-Za-z0-9_\-]*(?=\s*\())"), Role::Predicate},
      {QRegularExpression(R"(\b[A-Z_][A-Za-z0-9_]*\b)"), Role::Variable},
      {QRegularExpression(R"((?<![A-Za-z0-9_])-?\d+(\.\d+)?\b)"), Role::Number},
      {QRegularExpression(R"([@#][A-Za-z0-9_.]+)"), Role::Node},
      {QRegularExpression(R"("([^"\\]|\\.)*")"), Role::String},
  };
}

QTextCharFormat MeldHighlighter::format(Role role) const { return formats_[int(role)]; }

void MeldHighlighter::highlightBlock(const QString& text) {
  for (const Rule& rule : rules_) {
    auto it = rule.pattern.globalMatch(text);
    while (it.hasNext()) {
      const QRegularExpressionMatch m = it.next();
      setFormat(int(m.capturedStart()), int(m.capturedLength()), formats_[int(rule.role)]);
    }
  }
  // Comments last: they cover whatever the rules found inside them. A "//" or "/*" inside a
  // string does not start one.
  const QTextCharFormat& comment = formats_[int(Role::Comment)];
  setCurrentBlockState(kNormal);
  int i = 0;
  if (previousBlockState() == kInComment) {
    const int close = int(text.indexOf("*/"));
    if (close < 0) {
      setFormat(0, int(text.size()), comment);
      setCurrentBlockState(kInComment);
      return;
    }
    setFormat(0, close + 2, comment);
    i = close + 2;
  }
  bool inString = false;
  for (; i < text.size(); ++i) {
    const QChar c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      setFormat(i, int(text.size()) - i, comment);
      return;
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const int close = int(text.indexOf("*/", i + 2));
      if (close < 0) {
        setFormat(i, int(text.size()) - i, comment);
        setCurrentBlockState(kInComment);
        return;
      }
      setFormat(i, close + 2 - i, comment);
      i = close + 1;
    }
  }
}

}  // namespace ide
