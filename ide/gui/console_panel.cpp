#include "console_panel.hpp"

#include <QFontDatabase>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QTextDocument>
#include <QVBoxLayout>

namespace ide {

ConsolePanel::ConsolePanel(QWidget* parent)
    : QWidget(parent),
      filter_(new QLineEdit),
      search_(new QLineEdit),
      status_(new QLabel),
      text_(new QPlainTextEdit) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  auto* bar = new QHBoxLayout;
  filter_->setPlaceholderText("trace filter, e.g. blocks=0-9;kinds=message,color;from=1s;to=2s (Enter)");
  filter_->setToolTip("vsim --trace's filter language; empty: the programs' own output and trace lines only");
  search_->setPlaceholderText("search (Enter: next match)");
  search_->setClearButtonEnabled(true);
  auto* clear = new QPushButton("Clear");
  bar->addWidget(filter_, 3);
  bar->addWidget(search_, 2);
  bar->addWidget(clear);
  layout->addLayout(bar);
  layout->addWidget(status_);
  status_->hide();
  text_->setReadOnly(true);
  text_->setMaximumBlockCount(kMaxLines);
  text_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  text_->setLineWrapMode(QPlainTextEdit::NoWrap);
  layout->addWidget(text_, 1);
  connect(filter_, &QLineEdit::returnPressed, this,
          [this] { Q_EMIT traceFilterChanged(filter_->text().trimmed()); });
  connect(search_, &QLineEdit::returnPressed, this, [this] { find(false); });
  connect(clear, &QPushButton::clicked, text_, &QPlainTextEdit::clear);
}

void ConsolePanel::append(const std::vector<std::string>& lines) {
  for (const std::string& l : lines) text_->appendPlainText(QString::fromStdString(l));
}

void ConsolePanel::appendMessage(const QString& text) { text_->appendPlainText(text); }

QString ConsolePanel::text() const { return text_->toPlainText(); }

void ConsolePanel::setFilterError(const QString& error) {
  status_->setText(error.isEmpty() ? QString()
                                   : "<span style='color:#b00000'>" + error.toHtmlEscaped() + "</span>");
  status_->setVisible(!error.isEmpty());
}

void ConsolePanel::find(bool backward) {
  const QString needle = search_->text();
  if (needle.isEmpty()) return;
  const QTextDocument::FindFlags flags = backward ? QTextDocument::FindBackward : QTextDocument::FindFlags();
  if (text_->find(needle, flags)) return;
  // Wrap around once.
  QTextCursor c = text_->textCursor();
  c.movePosition(backward ? QTextCursor::End : QTextCursor::Start);
  text_->setTextCursor(c);
  text_->find(needle, flags);
}

}  // namespace ide
