// The selected block: id, cell, colour and neighbours per face; for a Meld program its current
// facts grouped by predicate (with counts), for a C BlockCode the text of its info callback; a
// filter box over the facts.
#pragma once

#include <QSet>
#include <QWidget>

#include "session_info.hpp"
#include "snapshot.hpp"

class QLabel;
class QLineEdit;
class QPlainTextEdit;
class QTreeWidget;

namespace ide {

class BlockInspector : public QWidget {
  Q_OBJECT
 public:
  explicit BlockInspector(QWidget* parent = nullptr);
  void setSession(const SessionInfo& info);
  void show(const BlockDetails& details);

  // What is shown, for tests: the fact lines of every predicate (filter applied), in order.
  QStringList factLines() const;
  QString headerText() const;
  void setFilter(const QString& text);

 private:
  void rebuildFacts();

  SessionInfo info_;
  BlockDetails shown_;
  QSet<QString> collapsed_;  // predicate groups the user closed
  QLabel* header_;
  QLineEdit* filter_;
  QTreeWidget* facts_;
  QPlainTextEdit* infoText_;
};

}  // namespace ide
