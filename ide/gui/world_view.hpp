// The 3D world: draws the latest snapshot through the WorldRenderer; left drag orbits, right or
// middle drag pans, the wheel zooms; hovering shows the block's id, a click selects it.
#pragma once

#include <QElapsedTimer>
#include <QOpenGLWidget>
#include <memory>

#include "orbit_camera.hpp"
#include "session_info.hpp"
#include "snapshot.hpp"

namespace ide {

class WorldRenderer;

class WorldView : public QOpenGLWidget {
  Q_OBJECT
 public:
  explicit WorldView(QWidget* parent = nullptr);
  ~WorldView() override;

  // A new session: the camera goes back to the world's <camera> with its first snapshot.
  void setSession(const SessionInfo& info);
  void setSnapshot(std::shared_ptr<const WorldSnapshot> snap);
  void setSelected(std::uint32_t block);
  // Centres the camera on the selected block.
  void focusSelected();
  OrbitCamera& camera() { return camera_; }
  // The block under a point of the widget, or kNoBlock.
  std::uint32_t blockAt(const QPoint& p) const;
  // Time of the last frames (ms, smoothed): from the start of drawing to the frame on screen.
  double frameMs() const { return frameMs_; }
  // Whether a new frame would keep drawing under `share` of the time (while the run goes as fast
  // as possible, the view draws only that often: a software renderer shares the run's cores).
  bool readyForFrame(double share) const;
  // The GL error, when the view cannot draw (no OpenGL 3.3).
  const QString& glError() const { return glError_; }

 Q_SIGNALS:
  void blockClicked(std::uint32_t block);

 protected:
  void initializeGL() override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;

 private:
  void releaseGl();

  std::unique_ptr<WorldRenderer> renderer_;
  std::shared_ptr<const WorldSnapshot> snap_;
  SessionInfo info_;
  bool sessionChanged_ = false, cameraSet_ = false;
  OrbitCamera camera_;
  std::uint32_t selected_ = 0xFFFFFFFFu, hovered_ = 0xFFFFFFFFu;
  QPoint pressPos_, lastPos_;
  bool dragging_ = false;
  double frameMs_ = 0;
  QElapsedTimer paintStart_, lastFrameEnd_;
  QString glError_;
  QMetaObject::Connection contextGone_;  // the context's aboutToBeDestroyed, to release GL objects
};

}  // namespace ide
