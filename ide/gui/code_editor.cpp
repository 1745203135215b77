#include "code_editor.hpp"

#include <QFile>
#include <QFileInfo>
#include <QFontDatabase>
#include <QPainter>
#include <QSaveFile>
#include <QTextBlock>

#include "meld_highlighter.hpp"

namespace ide {

namespace {

class LineNumberArea : public QWidget {
 public:
  explicit LineNumberArea(CodeEditor* editor) : QWidget(editor), editor_(editor) {}
  QSize sizeHint() const override { return QSize(editor_->lineNumberAreaWidth(), 0); }

 protected:
  void paintEvent(QPaintEvent* event) override { editor_->paintLineNumbers(event); }

 private:
  CodeEditor* editor_;
};

}  // namespace

CodeEditor::CodeEditor(QWidget* parent)
    : QPlainTextEdit(parent),
      lineNumbers_(new LineNumberArea(this)),
      highlighter_(new MeldHighlighter(document())) {
  setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  setLineWrapMode(QPlainTextEdit::NoWrap);
  setTabStopDistance(fontMetrics().horizontalAdvance(' ') * 2);
  connect(this, &QPlainTextEdit::blockCountChanged, this,
          [this] { setViewportMargins(lineNumberAreaWidth(), 0, 0, 0); });
  connect(this, &QPlainTextEdit::updateRequest, this, &CodeEditor::updateLineNumberArea);
  connect(this, &QPlainTextEdit::cursorPositionChanged, this, &CodeEditor::refreshSelections);
  // Edits move text under the marks: they belong to the text that was compiled.
  connect(document(), &QTextDocument::contentsChanged, this, [this] {
    if (diagnosticMarks_.isEmpty()) return;
    diagnosticMarks_.clear();
    refreshSelections();
  });
  setViewportMargins(lineNumberAreaWidth(), 0, 0, 0);
  refreshSelections();
}

bool CodeEditor::load(const QString& path, QString& error) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) {
    error = QString("cannot open '%1': %2").arg(path, file.errorString());
    return false;
  }
  setPlainText(QString::fromUtf8(file.readAll()));
  path_ = path;
  document()->setModified(false);
  return true;
}

bool CodeEditor::save(QString& error) {
  QSaveFile file(path_);
  if (path_.isEmpty() || !file.open(QIODevice::WriteOnly) || file.write(toPlainText().toUtf8()) < 0 ||
      !file.commit()) {
    error = QString("cannot write '%1': %2").arg(path_, file.errorString());
    return false;
  }
  document()->setModified(false);
  return true;
}

void CodeEditor::setDiagnostics(const std::vector<Diagnostic>& diagnostics) {
  diagnosticMarks_.clear();
  const QString mine = QFileInfo(path_).canonicalFilePath();
  for (const Diagnostic& d : diagnostics) {
    if (d.line < 1 || QFileInfo(d.file).canonicalFilePath() != mine) continue;
    const QTextBlock block = document()->findBlockByNumber(d.line - 1);
    if (!block.isValid()) continue;
    QTextCursor c(block);
    const int column = std::clamp(d.column - 1, 0, std::max(0, int(block.length()) - 1));
    c.setPosition(block.position() + column);
    // The word at the column, or one character.
    c.movePosition(QTextCursor::EndOfWord, QTextCursor::KeepAnchor);
    if (!c.hasSelection()) c.movePosition(QTextCursor::NextCharacter, QTextCursor::KeepAnchor);
    QTextEdit::ExtraSelection mark;
    mark.cursor = c;
    mark.format.setUnderlineStyle(QTextCharFormat::WaveUnderline);
    mark.format.setUnderlineColor(d.severity == "error" ? Qt::red : QColor(0xd0, 0x90, 0x00));
    mark.format.setToolTip(d.message);
    diagnosticMarks_.append(mark);
  }
  refreshSelections();
}

std::vector<std::pair<int, int>> CodeEditor::underlined() const {
  std::vector<std::pair<int, int>> out;
  for (const QTextEdit::ExtraSelection& s : diagnosticMarks_)
    out.emplace_back(s.cursor.selectionStart(), s.cursor.selectionEnd() - s.cursor.selectionStart());
  return out;
}

void CodeEditor::goTo(int line, int column) {
  const QTextBlock block = document()->findBlockByNumber(std::max(0, line - 1));
  if (!block.isValid()) return;
  QTextCursor c(block);
  c.setPosition(block.position() + std::clamp(column - 1, 0, std::max(0, int(block.length()) - 1)));
  setTextCursor(c);
  centerCursor();
  setFocus();
}

int CodeEditor::lineNumberAreaWidth() const {
  int digits = 1;
  for (int max = std::max(1, blockCount()); max >= 10; max /= 10) ++digits;
  return 8 + fontMetrics().horizontalAdvance(QLatin1Char('9')) * std::max(digits, 3);
}

void CodeEditor::updateLineNumberArea(const QRect& rect, int dy) {
  if (dy)
    lineNumbers_->scroll(0, dy);
  else
    lineNumbers_->update(0, rect.y(), lineNumbers_->width(), rect.height());
}

void CodeEditor::resizeEvent(QResizeEvent* event) {
  QPlainTextEdit::resizeEvent(event);
  const QRect r = contentsRect();
  lineNumbers_->setGeometry(QRect(r.left(), r.top(), lineNumberAreaWidth(), r.height()));
}

void CodeEditor::paintLineNumbers(QPaintEvent* event) {
  QPainter painter(lineNumbers_);
  painter.fillRect(event->rect(), QColor(0xf0, 0xf0, 0xf0));
  QTextBlock block = firstVisibleBlock();
  int top = qRound(blockBoundingGeometry(block).translated(contentOffset()).top());
  const int current = textCursor().blockNumber();
  while (block.isValid() && top <= event->rect().bottom()) {
    const int height = qRound(blockBoundingRect(block).height());
    if (block.isVisible() && top + height >= event->rect().top()) {
      painter.setPen(block.blockNumber() == current ? Qt::black : QColor(0x90, 0x90, 0x90));
      painter.drawText(0, top, lineNumbers_->width() - 4, fontMetrics().height(), Qt::AlignRight,
                       QString::number(block.blockNumber() + 1));
    }
    block = block.next();
    top += height;
  }
}

void CodeEditor::refreshSelections() {
  QList<QTextEdit::ExtraSelection> all;
  QTextEdit::ExtraSelection line;
  line.format.setBackground(QColor(0xff, 0xf8, 0xd8));
  line.format.setProperty(QTextFormat::FullWidthSelection, true);
  line.cursor = textCursor();
  line.cursor.clearSelection();
  all.append(line);
  all.append(diagnosticMarks_);
  setExtraSelections(all);
  lineNumbers_->update();
}

}  // namespace ide
