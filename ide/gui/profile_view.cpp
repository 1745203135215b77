#include "profile_view.hpp"

#include <QComboBox>
#include <QHeaderView>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QTableWidget>
#include <QToolTip>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

namespace ide {

namespace {

const QColor kIdle(214, 214, 214), kSteal(235, 140, 40), kBackground(250, 250, 250);

// Light to dark green with the span's facts per microsecond against the busiest span's.
QColor runColour(double rate, double maxRate) {
  const double k = std::clamp(maxRate > 0 ? rate / maxRate : 0.0, 0.0, 1.0);
  return QColor::fromRgbF(float(0.70 - 0.55 * k), float(0.88 - 0.38 * k), float(0.66 - 0.46 * k));
}

QString duration(double us) {
  if (us == 0) return "0";
  // At most three significant decimals, without trailing zeros ("500 ms", "1.25 s").
  auto number = [](double v, int decimals) {
    QString t = QString::number(v, 'f', decimals);
    if (t.contains('.')) {
      while (t.endsWith('0')) t.chop(1);
      if (t.endsWith('.')) t.chop(1);
    }
    return t;
  };
  if (us >= 1e6) return number(us / 1e6, 3) + " s";
  if (us >= 1e3) return number(us / 1e3, 2) + " ms";
  return number(us, 1) + " µs";
}

// A tick step of 1, 2 or 5 times a power of ten giving ticks at least `minUs` apart.
double tickStep(double minUs) {
  const double p = std::pow(10.0, std::floor(std::log10(std::max(minUs, 1e-3))));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= minUs) return m * p;
  return 10 * p;
}

QTableWidgetItem* cell(const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  return item;
}

}  // namespace

Timeline::Timeline(QWidget* parent) : QWidget(parent) {
  setMouseTracking(true);
  setMinimumHeight(kAxisHeight + 2 * rowHeight_ + 8);
}

void Timeline::setProfile(const Profile* profile) {
  profile_ = profile;
  maxRate_ = 0;
  if (profile_)
    for (const auto& spans : profile_->threads)
      for (const ProfileSpan& s : spans)
        if (s.kind == ProfileSpan::Kind::Run && s.endUs > s.beginUs)
          maxRate_ = std::max(maxRate_, double(s.facts) / (s.endUs - s.beginUs));
  const int rows = int(profile_ ? profile_->threads.size() : 1);
  rowHeight_ = std::clamp(500 / std::max(1, rows), 6, 30);
  setFixedHeight(kAxisHeight + rowHeight_ * rows + 8);
  resetZoom();
}

void Timeline::resetZoom() {
  begin_ = 0;
  end_ = profile_ && profile_->endUs > 0 ? profile_->endUs : 1;
  update();
}

double Timeline::xOf(double us) const {
  return kLabelWidth + (us - begin_) / (end_ - begin_) * double(width() - kLabelWidth - 8);
}

double Timeline::usAt(double x) const {
  return begin_ + (x - kLabelWidth) / double(std::max(1, width() - kLabelWidth - 8)) * (end_ - begin_);
}

void Timeline::drawAxis(QPainter& g) {
  const double step = tickStep((end_ - begin_) * 90.0 / std::max(1, width() - kLabelWidth));
  g.setPen(QColor(90, 90, 90));
  for (double t = std::ceil(begin_ / step) * step; t <= end_; t += step) {
    const int x = int(xOf(t));
    g.drawLine(x, kAxisHeight - 6, x, kAxisHeight);
    g.drawText(x + 3, kAxisHeight - 9, duration(t));
  }
}

void Timeline::paintEvent(QPaintEvent*) {
  QPainter g(this);
  g.fillRect(rect(), kBackground);
  if (!profile_) return;
  drawAxis(g);
  for (std::size_t t = 0; t < profile_->threads.size(); ++t) {
    const int y = kAxisHeight + int(t) * rowHeight_;
    g.setPen(Qt::black);
    if (rowHeight_ >= 12)
      g.drawText(QRect(4, y, kLabelWidth - 8, rowHeight_), Qt::AlignVCenter, profile_->laneNames[t]);
    g.setPen(Qt::NoPen);
    for (const ProfileSpan& s : profile_->threads[t]) {
      if (s.endUs < begin_ || s.beginUs > end_) continue;
      const double x0 = std::max(xOf(s.beginUs), double(kLabelWidth)), x1 = xOf(s.endUs);
      QColor c = s.kind == ProfileSpan::Kind::Idle ? kIdle
                 : s.kind == ProfileSpan::Kind::Steal
                     ? kSteal
                     : runColour(double(s.facts) / std::max(1e-9, s.endUs - s.beginUs), maxRate_);
      const int pad = rowHeight_ >= 12 ? 4 : 1;
      g.fillRect(QRectF(x0, y + pad, std::max(1.0, x1 - x0), rowHeight_ - 2 * pad), c);
    }
  }
}

void Timeline::wheelEvent(QWheelEvent* e) {
  // Zoom around the time under the mouse: in with the wheel forward.
  const double at = usAt(e->position().x()), factor = e->angleDelta().y() > 0 ? 0.8 : 1.25;
  const double span = std::max(1.0, (end_ - begin_) * factor);
  begin_ = at - (at - begin_) * factor;
  end_ = begin_ + span;
  update();
}

void Timeline::mousePressEvent(QMouseEvent* e) {
  dragFrom_ = e->position().x();
  dragBegin_ = begin_;
}

void Timeline::mouseMoveEvent(QMouseEvent* e) {
  if (e->buttons() & Qt::LeftButton && dragFrom_ >= 0) {
    const double shift = usAt(dragFrom_) - usAt(e->position().x()), span = end_ - begin_;
    begin_ = dragBegin_ + shift;
    end_ = begin_ + span;
    update();
    return;
  }
  int thread = 0;
  if (const ProfileSpan* s = spanAt(e->position().toPoint(), thread)) {
    const QString what = s->kind == ProfileSpan::Kind::Idle ? "idle"
                         : s->kind == ProfileSpan::Kind::Steal
                             ? QString("rebalance: %1 nodes taken").arg(s->nodeRuns)
                             : QString("%1 node runs, %2 facts derived").arg(s->nodeRuns).arg(s->facts);
    QToolTip::showText(e->globalPosition().toPoint(),
                       QString("%1, %2 from %3: %4")
                           .arg(profile_->laneNames[std::size_t(thread)])
                           .arg(duration(s->endUs - s->beginUs), duration(s->beginUs), what),
                       this);
  } else {
    QToolTip::hideText();
  }
}

const ProfileSpan* Timeline::spanAt(QPoint p, int& thread) const {
  if (!profile_ || p.x() < kLabelWidth || p.y() < kAxisHeight) return nullptr;
  thread = (p.y() - kAxisHeight) / rowHeight_;
  if (std::size_t(thread) >= profile_->threads.size()) return nullptr;
  const double at = usAt(p.x());
  const auto& spans = profile_->threads[std::size_t(thread)];
  auto it = std::upper_bound(spans.begin(), spans.end(), at,
                             [](double v, const ProfileSpan& s) { return v < s.beginUs; });
  if (it == spans.begin()) return nullptr;
  --it;
  return at <= it->endUs ? &*it : nullptr;
}

ProfileView::ProfileView(std::vector<Profile> profiles, QWidget* parent)
    : QWidget(parent), profiles_(std::move(profiles)) {
  auto* layout = new QVBoxLayout(this);
  chooser_ = new QComboBox(this);
  for (const Profile& p : profiles_) chooser_->addItem(p.title + "  (" + p.path + ")");
  chooser_->setVisible(profiles_.size() > 1);
  heading_ = new QLabel(this);
  timeline_ = new Timeline(this);
  summary_ = new QTableWidget(this);
  summary_->setColumnCount(7);
  summary_->setHorizontalHeaderLabels(
      {"thread / core", "busy %", "idle %", "steal %", "node runs", "facts derived", "nodes stolen"});
  summary_->verticalHeader()->hide();
  summary_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  sweep_ = new QTableWidget(this);
  sweep_->setColumnCount(4);
  sweep_->setHorizontalHeaderLabels({"threads / cores", "wall s (chip: predicted)", "speedup", "efficiency"});
  sweep_->verticalHeader()->hide();
  sweep_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  const std::vector<SweepRow> rows = sweep(profiles_);
  sweep_->setRowCount(int(rows.size()));
  for (int r = 0; r < int(rows.size()); ++r) {
    sweep_->setItem(r, 0, cell(QString::number(rows[std::size_t(r)].threads)));
    sweep_->setItem(r, 1, cell(QString::number(rows[std::size_t(r)].wallSeconds, 'f', 3)));
    sweep_->setItem(r, 2, cell(QString::number(rows[std::size_t(r)].speedup, 'f', 2)));
    sweep_->setItem(r, 3, cell(QString::number(rows[std::size_t(r)].efficiency, 'f', 2)));
  }
  auto* legend = new QLabel(
      "<span style='background:#4a8a3a;color:white'>&nbsp;node runs (darker: more facts/ms)&nbsp;</span> "
      "<span style='background:#d6d6d6'>&nbsp;idle&nbsp;</span> "
      "<span style='background:#eb8c28'>&nbsp;steal (rebalance)&nbsp;</span> &nbsp; wheel: zoom, drag: pan, "
      "double-click: all",
      this);
  layout->addWidget(chooser_);
  layout->addWidget(heading_);
  layout->addWidget(timeline_);
  layout->addWidget(legend);
  layout->addWidget(summary_, 2);
  auto* sweepLabel = new QLabel(
      "Speedup over the run with the fewest threads or cores (the profiles opened together):", this);
  layout->addWidget(sweepLabel);
  layout->addWidget(sweep_, 1);
  sweepLabel->setVisible(profiles_.size() > 1);
  sweep_->setVisible(profiles_.size() > 1);
  connect(chooser_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int i) { showProfile(i); });
  // The most threads first: the run one opens a profile for.
  const auto most = std::max_element(
      profiles_.begin(), profiles_.end(),
      [](const Profile& a, const Profile& b) { return a.threads.size() < b.threads.size(); });
  const int first = profiles_.empty() ? -1 : int(most - profiles_.begin());
  if (first >= 0) chooser_->setCurrentIndex(first);
  showProfile(first);
}

void ProfileView::showProfile(int index) {
  if (index < 0 || std::size_t(index) >= profiles_.size()) {
    timeline_->setProfile(nullptr);
    return;
  }
  const Profile& p = profiles_[std::size_t(index)];
  heading_->setText(QString(p.simulated ? "<b>%1</b> — %2 simulated cores, predicted %3 s"
                                        : "<b>%1</b> — %2 worker threads, %3 s")
                        .arg(p.title)
                        .arg(p.threads.size())
                        .arg(p.endUs / 1e6, 0, 'f', 3));
  timeline_->setProfile(&p);
  summary_->setRowCount(int(p.summary.size()));
  for (int t = 0; t < int(p.summary.size()); ++t) {
    const ThreadSummary& s = p.summary[std::size_t(t)];
    const double total = std::max(1e-9, p.endUs);
    summary_->setItem(t, 0, cell(p.laneNames[std::size_t(t)]));
    summary_->setItem(t, 1, cell(QString::number(100 * s.runUs / total, 'f', 1)));
    summary_->setItem(t, 2, cell(QString::number(100 * s.idleUs / total, 'f', 1)));
    summary_->setItem(t, 3, cell(QString::number(100 * s.stealUs / total, 'f', 1)));
    summary_->setItem(t, 4, cell(QString::number(s.nodeRuns)));
    summary_->setItem(t, 5, cell(QString::number(s.facts)));
    summary_->setItem(t, 6, cell(QString::number(s.nodesTaken)));
  }
}

}  // namespace ide
