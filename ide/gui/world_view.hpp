// The 3D world: draws the latest snapshot through the WorldRenderer; left drag orbits, right or
// middle drag pans, the wheel zooms; hovering shows the block's id, a click selects it.
#pragma once

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
  // Mean time of the last frames drawn (ms), for the status bar.
  double frameMs() const { return frameMs_; }
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
  QString glError_;
};

}  // namespace ide
