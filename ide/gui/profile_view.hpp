// The profile view of the multicore target: one or more `meld --profile` files. Per worker
// thread, a timeline of node runs (darker: more facts derived per ms), idle time and steals, with
// zoom (wheel), pan (drag) and the span under the mouse in a tooltip; the busy/idle/steal summary
// per thread; and with several profiles of one program (a -j sweep), the speedup table.
#pragma once

#include <QWidget>
#include <vector>

#include "profile_data.hpp"

class QComboBox;
class QLabel;
class QTableWidget;

namespace ide {

class Timeline : public QWidget {
  Q_OBJECT
 public:
  explicit Timeline(QWidget* parent = nullptr);
  void setProfile(const Profile* profile);
  void resetZoom();
  QSize sizeHint() const override { return {900, 60 + 34 * 4}; }
  // The time range shown, in microseconds (tests, the zoom label).
  double viewBegin() const { return begin_; }
  double viewEnd() const { return end_; }

 protected:
  void paintEvent(QPaintEvent*) override;
  void wheelEvent(QWheelEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseDoubleClickEvent(QMouseEvent*) override { resetZoom(); }

 private:
  double xOf(double us) const;
  double usAt(double x) const;
  const ProfileSpan* spanAt(QPoint p, int& thread) const;
  void drawAxis(QPainter& g);

  const Profile* profile_ = nullptr;
  double begin_ = 0, end_ = 1, maxRate_ = 1;  // facts per microsecond of the busiest span
  double dragFrom_ = -1, dragBegin_ = 0;
  static constexpr int kLabelWidth = 84, kAxisHeight = 26;
  int rowHeight_ = 30;  // thinner rows for many threads: all of them fit in about 500 pixels
};

class ProfileView : public QWidget {
  Q_OBJECT
 public:
  explicit ProfileView(std::vector<Profile> profiles, QWidget* parent = nullptr);
  const std::vector<Profile>& profiles() const { return profiles_; }
  QTableWidget* summaryTable() const { return summary_; }
  QTableWidget* sweepTable() const { return sweep_; }
  Timeline* timeline() const { return timeline_; }

 private:
  void showProfile(int index);

  std::vector<Profile> profiles_;
  QComboBox* chooser_;
  QLabel* heading_;
  Timeline* timeline_;
  QTableWidget* summary_;
  QTableWidget* sweep_;
};

}  // namespace ide
