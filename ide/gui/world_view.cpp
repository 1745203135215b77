#include "world_view.hpp"

#include <QElapsedTimer>
#include <QMouseEvent>
#include <QToolTip>
#include <QWheelEvent>
#include <algorithm>

#include "offscreen_render.hpp"
#include "world_renderer.hpp"

namespace ide {

WorldView::WorldView(QWidget* parent) : QOpenGLWidget(parent) {
  setMouseTracking(true);
  setMinimumSize(200, 150);
  connect(this, &QOpenGLWidget::frameSwapped, this, [this] {
    if (!paintStart_.isValid()) return;
    frameMs_ = 0.7 * frameMs_ + 0.3 * double(paintStart_.nsecsElapsed()) / 1e6;
    lastFrameEnd_.start();
  });
}

bool WorldView::readyForFrame(double share) const {
  if (!lastFrameEnd_.isValid()) return true;
  return double(lastFrameEnd_.elapsed()) >= frameMs_ * (1.0 - share) / share;
}

WorldView::~WorldView() {
  // QOpenGLWidget's destructor destroys the context after this object is gone: the slot must not
  // be called then (UBSan found the call on the half-destroyed widget).
  disconnect(contextGone_);
  releaseGl();
}

void WorldView::releaseGl() {
  if (!renderer_) return;
  makeCurrent();
  renderer_.reset();
  doneCurrent();
}

void WorldView::setSession(const SessionInfo& info) {
  info_ = info;
  sessionChanged_ = true;
  cameraSet_ = false;
  selected_ = hovered_ = 0xFFFFFFFFu;
  update();
}

void WorldView::setSnapshot(std::shared_ptr<const WorldSnapshot> snap) {
  snap_ = std::move(snap);
  if (snap_ && !cameraSet_) {
    camera_ = initialCamera(info_, *snap_);
    cameraSet_ = true;
  }
  update();
}

void WorldView::setSelected(std::uint32_t block) {
  selected_ = block;
  update();
}

void WorldView::focusSelected() {
  if (!snap_ || selected_ >= snap_->positions.size()) return;
  const auto& p = snap_->positions[selected_];
  camera_.focus(QVector3D(p[0], p[1], p[2]));
  update();
}

std::uint32_t WorldView::blockAt(const QPoint& p) const {
  if (!snap_) return 0xFFFFFFFFu;
  QVector3D origin, direction;
  camera_.ray(float(p.x()), float(p.y()), width(), height(), origin, direction);
  const float radius = 0.5f * *std::min_element(info_.blockSizeMm.begin(), info_.blockSizeMm.end());
  return pickBlock(origin, direction, snap_->positions, snap_->alive, radius);
}

void WorldView::initializeGL() {
  renderer_ = std::make_unique<WorldRenderer>();
  if (!renderer_->initialize()) {
    glError_ = "OpenGL 3.3 is not available: " + renderer_->log();
    renderer_.reset();
  }
  sessionChanged_ = true;
  disconnect(contextGone_);
  contextGone_ = connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &WorldView::releaseGl);
}

void WorldView::paintGL() {
  if (!renderer_) return;
  paintStart_.start();
  if (sessionChanged_) {
    renderer_->setSession(info_);
    sessionChanged_ = false;
  }
  if (snap_) renderer_->upload(*snap_);
  renderer_->setHighlight(selected_, hovered_);
  const qreal ratio = devicePixelRatioF();
  renderer_->render(camera_, int(width() * ratio), int(height() * ratio));
}

void WorldView::mousePressEvent(QMouseEvent* e) {
  pressPos_ = lastPos_ = e->pos();
  dragging_ = false;
}

void WorldView::mouseMoveEvent(QMouseEvent* e) {
  const QPoint delta = e->pos() - lastPos_;
  lastPos_ = e->pos();
  if (e->buttons() != Qt::NoButton) {
    if ((e->pos() - pressPos_).manhattanLength() > 3) dragging_ = true;
    if (!dragging_) return;
    if (e->buttons() & Qt::LeftButton)
      camera_.orbit(-0.4f * float(delta.x()), 0.4f * float(delta.y()));
    else
      camera_.pan(float(delta.x()) / float(std::max(height(), 1)),
                  -float(delta.y()) / float(std::max(height(), 1)));
    update();
    return;
  }
  const std::uint32_t hovered = blockAt(e->pos());
  if (hovered != hovered_) {
    hovered_ = hovered;
    if (hovered == 0xFFFFFFFFu)
      QToolTip::hideText();
    else
      QToolTip::showText(e->globalPosition().toPoint(), QString("block %1").arg(hovered), this);
    update();
  }
}

void WorldView::mouseReleaseEvent(QMouseEvent* e) {
  if (!dragging_ && e->button() == Qt::LeftButton) Q_EMIT blockClicked(blockAt(e->pos()));
  dragging_ = false;
}

void WorldView::wheelEvent(QWheelEvent* e) {
  camera_.zoom(e->angleDelta().y() > 0 ? 1.0f / 1.15f : 1.15f);
  update();
}

}  // namespace ide
