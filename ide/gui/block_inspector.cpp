#include "block_inspector.hpp"

#include <QCheckBox>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPlainTextEdit>
#include <QScrollBar>
#include <QSet>
#include <QTabWidget>
#include <QTreeWidget>
#include <QVBoxLayout>
#include <functional>

namespace ide {

namespace {

QString colorText(std::uint32_t rgb) {
  return QString("<span style='background:#%1'>&nbsp;&nbsp;&nbsp;&nbsp;</span> #%1")
      .arg(rgb & 0xFFFFFF, 6, 16, QChar('0'));
}

bool sameFacts(const BlockDetails& a, const BlockDetails& b) {
  if (a.facts.size() != b.facts.size()) return false;
  for (std::size_t i = 0; i < a.facts.size(); ++i)
    if (a.facts[i].predicate != b.facts[i].predicate || a.facts[i].lines != b.facts[i].lines) return false;
  return true;
}

}  // namespace

BlockInspector::BlockInspector(QWidget* parent)
    : QWidget(parent),
      header_(new QLabel),
      filter_(new QLineEdit),
      facts_(new QTreeWidget),
      infoText_(new QPlainTextEdit),
      tabs_(new QTabWidget),
      why_(new QTreeWidget),
      history_(new QListWidget),
      recordHistory_(new QCheckBox("Record the history of the selected block")) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  header_->setTextFormat(Qt::RichText);
  header_->setWordWrap(true);
  // The header wraps to the pane's width instead of widening the pane past the window's edge.
  header_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  header_->setMinimumWidth(120);
  header_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  filter_->setPlaceholderText("filter facts");
  filter_->setClearButtonEnabled(true);
  facts_->setHeaderLabels({"facts"});
  facts_->header()->setStretchLastSection(true);
  facts_->setUniformRowHeights(true);
  infoText_->setReadOnly(true);
  layout->addWidget(header_);
  layout->addWidget(filter_);
  layout->addWidget(facts_, 2);
  layout->addWidget(infoText_, 1);
  why_->setHeaderLabels({"fact", "how it came"});
  why_->setToolTip("Click a fact above to see why it exists; click a rule or axiom to open it");
  auto* historyPage = new QWidget;
  auto* historyLayout = new QVBoxLayout(historyPage);
  historyLayout->setContentsMargins(0, 0, 0, 0);
  historyLayout->addWidget(recordHistory_);
  historyLayout->addWidget(history_);
  tabs_->addTab(why_, "Why");
  tabs_->addTab(historyPage, "History");
  layout->addWidget(tabs_, 2);
  connect(filter_, &QLineEdit::textChanged, this, [this] {
    rebuildFacts();
    rebuildHistory();
  });
  connect(facts_, &QTreeWidget::itemClicked, this, [this](QTreeWidgetItem* item) {
    if (item->parent() && shown_.id != simcore::kNoBlock) Q_EMIT factChosen(shown_.id, item->text(0));
  });
  connect(why_, &QTreeWidget::itemClicked, this, [this](QTreeWidgetItem* item) {
    const QString where = item->data(0, Qt::UserRole).toString();
    const auto colon = where.lastIndexOf(':');
    if (colon > 0) Q_EMIT sourceClicked(where.left(colon), where.mid(colon + 1).toInt());
  });
  connect(recordHistory_, &QCheckBox::toggled, this, &BlockInspector::historyToggled);
  setSession(SessionInfo{});
}

void BlockInspector::setSession(const SessionInfo& info) {
  info_ = info;
  shown_ = BlockDetails{};
  facts_->setVisible(info.meld);
  filter_->setVisible(info.meld);
  tabs_->setTabEnabled(0, info.meld);
  why_->clear();
  history_->clear();
  shownWhy_ = 0;
  infoText_->setVisible(!info.meld && !info.codePath.empty());
  show(BlockDetails{});
}

void BlockInspector::show(const BlockDetails& d) {
  if (d.id == simcore::kNoBlock) {
    header_->setText("<i>No block selected: click one in the 3D view.</i>");
  } else {
    QString text = QString("<b>block %1</b>%2<br>cell (%3, %4, %5) &nbsp; %6")
                       .arg(d.id)
                       .arg(!d.alive   ? " (removed)"
                            : d.moving ? " (moving)"
                                       : "")
                       .arg(d.cell.x)
                       .arg(d.cell.y)
                       .arg(d.cell.z)
                       .arg(colorText(d.color));
    text += "<br>neighbours: ";
    QStringList faces;
    for (const auto& [face, block] : d.neighbors)
      faces << QString("%1 %2").arg(QString::fromStdString(face),
                                    block == simcore::kNoBlock ? "–" : QString::number(block));
    text += faces.join(", ");
    header_->setText(text);
  }
  infoText_->setPlainText(QString::fromStdString(d.info));
  const bool factsChanged = d.id != shown_.id || !sameFacts(d, shown_);
  const bool historyChanged = d.id != shown_.id || d.history.size() != shown_.history.size() ||
                              (!d.history.empty() && d.history.back().text != shown_.history.back().text);
  shown_ = d;
  if (factsChanged) rebuildFacts();
  if (historyChanged) rebuildHistory();
}

void BlockInspector::showWhy(const WhyResult& why) {
  if (why.request == shownWhy_) return;
  shownWhy_ = why.request;
  why_->clear();
  tabs_->setCurrentIndex(0);
  if (why.lines.empty()) {
    why_->addTopLevelItem(
        new QTreeWidgetItem({QString::fromStdString(why.fact), QString::fromStdString(why.error)}));
    return;
  }
  std::vector<QTreeWidgetItem*> parents;  // by depth
  for (const meldvm::WhyLine& l : why.lines) {
    auto* item = new QTreeWidgetItem({QString::fromStdString(l.fact), QString::fromStdString(l.how)});
    item->setData(0, Qt::UserRole, QString::fromStdString(l.where));
    item->setToolTip(0, QString::fromStdString(l.fact + "\n" + l.how));
    item->setToolTip(
        1, QString::fromStdString(l.how) +
               (l.where.empty() ? QString() : "\nClick to open " + QString::fromStdString(l.where)));
    parents.resize(std::size_t(l.depth));
    if (parents.empty())
      why_->addTopLevelItem(item);
    else
      parents.back()->addChild(item);
    parents.push_back(item);
  }
  why_->expandAll();
  why_->resizeColumnToContents(0);
}

void BlockInspector::rebuildHistory() {
  history_->clear();
  const QString filter = filter_->text();
  for (const HistoryEntry& e : shown_.history) {
    const QString line = QString("%1  %2").arg(QString::fromStdString(simcore::formatTime(e.time)),
                                               QString::fromStdString(e.text));
    if (filter.isEmpty() || line.contains(filter, Qt::CaseInsensitive)) history_->addItem(line);
  }
  history_->scrollToBottom();
}

QStringList BlockInspector::whyRows() const {
  QStringList rows;
  std::function<void(const QTreeWidgetItem*, int)> walk = [&](const QTreeWidgetItem* item, int depth) {
    rows << QString(depth * 2, ' ') + item->text(0) + "    " + item->text(1);
    for (int i = 0; i < item->childCount(); ++i) walk(item->child(i), depth + 1);
  };
  for (int i = 0; i < why_->topLevelItemCount(); ++i) walk(why_->topLevelItem(i), 0);
  return rows;
}

QStringList BlockInspector::historyLines() const {
  QStringList lines;
  for (int i = 0; i < history_->count(); ++i) lines << history_->item(i)->text();
  return lines;
}

bool BlockInspector::chooseFact(const QString& line) {
  for (int i = 0; i < facts_->topLevelItemCount(); ++i) {
    QTreeWidgetItem* group = facts_->topLevelItem(i);
    for (int j = 0; j < group->childCount(); ++j)
      if (group->child(j)->text(0) == line) {
        facts_->setCurrentItem(group->child(j));
        Q_EMIT facts_->itemClicked(group->child(j), 0);
        return true;
      }
  }
  return false;
}

void BlockInspector::setHistoryRecorded(bool on) { recordHistory_->setChecked(on); }

void BlockInspector::clickFirstWhyRow() {
  if (why_->topLevelItemCount() > 0) Q_EMIT why_->itemClicked(why_->topLevelItem(0), 0);
}

void BlockInspector::rebuildFacts() {
  // Groups the user collapsed stay collapsed (for every block), and the scroll position stays.
  for (int i = 0; i < facts_->topLevelItemCount(); ++i) {
    const QTreeWidgetItem* item = facts_->topLevelItem(i);
    const QString name = item->data(0, Qt::UserRole).toString();
    if (item->isExpanded())
      collapsed_.remove(name);
    else
      collapsed_.insert(name);
  }
  const int scroll = facts_->verticalScrollBar()->value();
  facts_->clear();
  const QString filter = filter_->text();
  for (const FactGroup& g : shown_.facts) {
    const QString name = QString::fromStdString(g.predicate);
    auto* group = new QTreeWidgetItem;
    int shownLines = 0;
    for (const std::string& line : g.lines) {
      const QString text = QString::fromStdString(line);
      if (!filter.isEmpty() && !text.contains(filter, Qt::CaseInsensitive)) continue;
      new QTreeWidgetItem(group, {text});
      ++shownLines;
    }
    if (shownLines == 0) {
      delete group;
      continue;
    }
    group->setText(0, QString("%1%2  (%3, %4)")
                          .arg(g.persistent ? "!" : "", name)
                          .arg(g.persistent ? "persistent" : "linear")
                          .arg(shownLines));
    group->setData(0, Qt::UserRole, name);
    facts_->addTopLevelItem(group);
    group->setExpanded(!collapsed_.contains(name) || !filter.isEmpty());
  }
  facts_->verticalScrollBar()->setValue(scroll);
}

QStringList BlockInspector::factLines() const {
  QStringList out;
  for (int i = 0; i < facts_->topLevelItemCount(); ++i) {
    const QTreeWidgetItem* group = facts_->topLevelItem(i);
    for (int j = 0; j < group->childCount(); ++j) out << group->child(j)->text(0);
  }
  return out;
}

QString BlockInspector::headerText() const { return header_->text(); }

void BlockInspector::setFilter(const QString& text) { filter_->setText(text); }

}  // namespace ide
