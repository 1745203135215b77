// Meld syntax colouring for the program editor: keywords, types, predicates, variables, numbers,
// strings, node literals, and `//` and `/* */` comments (the latter across lines, carried in the
// block state). The word lists are the reference's (docs/meld-language.md §1.3).
#pragma once

#include <QRegularExpression>
#include <QSyntaxHighlighter>
#include <QTextCharFormat>
#include <vector>

namespace ide {

class MeldHighlighter : public QSyntaxHighlighter {
  Q_OBJECT
 public:
  enum class Role { Keyword, Type, Predicate, Variable, Number, String, Node, Comment };
  explicit MeldHighlighter(QTextDocument* document);
  // The format used for a role (tests compare the formats of characters with these).
  QTextCharFormat format(Role role) const;

 protected:
  void highlightBlock(const QString& text) override;

 private:
  struct Rule {
    QRegularExpression pattern;
    Role role;
  };
  std::vector<Rule> rules_;
  QTextCharFormat formats_[8];
};

}  // namespace ide
