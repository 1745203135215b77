// The program editor: a plain-text editor with line numbers, the current line highlighted, Meld
// colouring, and the compiler's diagnostics underlined at their line and column.
#pragma once

#include <QPlainTextEdit>
#include <vector>

#include "diagnostics.hpp"

namespace ide {

class MeldHighlighter;

class CodeEditor : public QPlainTextEdit {
  Q_OBJECT
 public:
  explicit CodeEditor(QWidget* parent = nullptr);
  // Loads a file; false (and `error`) when it cannot be read.
  bool load(const QString& path, QString& error);
  bool save(QString& error);
  const QString& path() const { return path_; }

  // Underlines these (those of this editor's file only).
  void setDiagnostics(const std::vector<Diagnostic>& diagnostics);
  // The underlined ranges: (position, length) in the document, for tests.
  std::vector<std::pair<int, int>> underlined() const;
  // Puts the cursor at line:column (1-based) and shows it.
  void goTo(int line, int column);

  int lineNumberAreaWidth() const;
  void paintLineNumbers(QPaintEvent* event);
  MeldHighlighter* highlighter() const { return highlighter_; }

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void updateLineNumberArea(const QRect& rect, int dy);
  void refreshSelections();

  QWidget* lineNumbers_;
  MeldHighlighter* highlighter_;
  QString path_;
  QList<QTextEdit::ExtraSelection> diagnosticMarks_;
};

}  // namespace ide
