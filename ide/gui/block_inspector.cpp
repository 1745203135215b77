#include "block_inspector.hpp"

#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QScrollBar>
#include <QSet>
#include <QTreeWidget>
#include <QVBoxLayout>

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
      infoText_(new QPlainTextEdit) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  header_->setTextFormat(Qt::RichText);
  header_->setWordWrap(true);
  header_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  filter_->setPlaceholderText("filter facts");
  filter_->setClearButtonEnabled(true);
  facts_->setHeaderLabels({"facts"});
  facts_->header()->setStretchLastSection(true);
  facts_->setUniformRowHeights(true);
  infoText_->setReadOnly(true);
  layout->addWidget(header_);
  layout->addWidget(filter_);
  layout->addWidget(facts_, 1);
  layout->addWidget(infoText_, 1);
  connect(filter_, &QLineEdit::textChanged, this, [this] { rebuildFacts(); });
  setSession(SessionInfo{});
}

void BlockInspector::setSession(const SessionInfo& info) {
  info_ = info;
  shown_ = BlockDetails{};
  facts_->setVisible(info.meld);
  filter_->setVisible(info.meld);
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
  shown_ = d;
  if (factsChanged) rebuildFacts();
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
