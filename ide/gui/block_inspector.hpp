// The selected block: id, cell, colour and neighbours per face; for a Meld program its current
// facts grouped by predicate (with counts), for a C BlockCode the text of its info callback; a
// filter box over the facts and the history. Below, two tabs: why the chosen fact exists (its
// derivation tree; a click on a rule or axiom opens the program there) and the block's history
// (recorded only while its box is ticked).
#pragma once

#include <QSet>
#include <QWidget>

#include "session_info.hpp"
#include "snapshot.hpp"

class QLabel;
class QLineEdit;
class QCheckBox;
class QListWidget;
class QPlainTextEdit;
class QTabWidget;
class QTreeWidget;

namespace ide {

class BlockInspector : public QWidget {
  Q_OBJECT
 public:
  explicit BlockInspector(QWidget* parent = nullptr);
  void setSession(const SessionInfo& info);
  void show(const BlockDetails& details);
  void showWhy(const WhyResult& why);

  // What is shown, for tests: the fact lines of every predicate (filter applied), in order.
  QStringList factLines() const;
  QString headerText() const;
  void setFilter(const QString& text);
  // For tests: the why tree's rows (indented by depth, "fact    how") and the history's lines.
  QStringList whyRows() const;
  QStringList historyLines() const;
  // Chooses a fact line of the facts tree as a click would.
  bool chooseFact(const QString& line);
  // Clicks the why tree's first row (the fact asked about) as a user would.
  void clickFirstWhyRow();
  void setHistoryRecorded(bool on);

 Q_SIGNALS:
  void factChosen(std::uint32_t block, const QString& fact);  // a fact line was clicked: why?
  void sourceClicked(const QString& file, int line);          // a rule or axiom of the why tree
  void historyToggled(bool on);

 private:
  void rebuildFacts();
  void rebuildHistory();

  SessionInfo info_;
  BlockDetails shown_;
  QSet<QString> collapsed_;  // predicate groups the user closed
  QLabel* header_;
  QLineEdit* filter_;
  QTreeWidget* facts_;
  QPlainTextEdit* infoText_;
  QTabWidget* tabs_;
  QTreeWidget* why_;
  QListWidget* history_;
  QCheckBox* recordHistory_;
  std::uint64_t shownWhy_ = 0;
};

}  // namespace ide
