// The console: the programs' output and the run's trace lines, filtered with vsim --trace's
// language (blocks, kinds, time range), with search; a bounded number of lines is kept.
#pragma once

#include <QWidget>
#include <string>
#include <vector>

class QLineEdit;
class QPlainTextEdit;
class QLabel;

namespace ide {

class ConsolePanel : public QWidget {
  Q_OBJECT
 public:
  static constexpr int kMaxLines = 10000;
  explicit ConsolePanel(QWidget* parent = nullptr);
  void append(const std::vector<std::string>& lines);
  void appendMessage(const QString& text);  // the IDE's own messages (errors, restarts)
  QString text() const;
  void setFilterError(const QString& error);

 Q_SIGNALS:
  // The trace filter the user entered ("" = the programs' own lines only).
  void traceFilterChanged(const QString& filter);

 private:
  void find(bool backward);

  QLineEdit* filter_;
  QLineEdit* search_;
  QLabel* status_;
  QPlainTextEdit* text_;
};

}  // namespace ide
