#include "offscreen_render.hpp"

#include <QElapsedTimer>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QOpenGLFunctions>
#include <limits>

#include "world_renderer.hpp"

namespace ide {

OrbitCamera initialCamera(const SessionInfo& info, const WorldSnapshot& snap) {
  OrbitCamera camera;
  if (info.camera) {
    camera.set(*info.camera);
    return camera;
  }
  QVector3D lo(std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
               std::numeric_limits<float>::max());
  QVector3D hi = -lo;
  bool any = false;
  for (std::size_t b = 0; b < snap.positions.size(); ++b) {
    if (!snap.alive[b]) continue;
    const QVector3D p(snap.positions[b][0], snap.positions[b][1], snap.positions[b][2]);
    lo = QVector3D(std::min(lo.x(), p.x()), std::min(lo.y(), p.y()), std::min(lo.z(), p.z()));
    hi = QVector3D(std::max(hi.x(), p.x()), std::max(hi.y(), p.y()), std::max(hi.z(), p.z()));
    any = true;
  }
  if (!any) lo = hi = QVector3D(0, 0, 0);
  const QVector3D half(info.blockSizeMm[0] * 0.5f, info.blockSizeMm[1] * 0.5f, info.blockSizeMm[2] * 0.5f);
  camera.frame(lo - half, hi + half);
  return camera;
}

OffscreenRenderer::OffscreenRenderer() = default;

OffscreenRenderer::~OffscreenRenderer() {
  if (renderer_ && context_.makeCurrent(&surface_)) {
    renderer_.reset();
    context_.doneCurrent();
  }
}

bool OffscreenRenderer::initialize(const SessionInfo& info, QSize size, QString& error) {
  context_.setFormat(QSurfaceFormat::defaultFormat());
  if (!context_.create()) {
    error = "cannot create an OpenGL context";
    return false;
  }
  surface_.setFormat(context_.format());
  surface_.create();
  if (!context_.makeCurrent(&surface_)) {
    error = "cannot make the OpenGL context current on an offscreen surface";
    return false;
  }
  const QSurfaceFormat f = context_.format();
  if (f.majorVersion() * 10 + f.minorVersion() < 33) {
    error =
        QString("OpenGL 3.3 is needed, the context has %1.%2").arg(f.majorVersion()).arg(f.minorVersion());
    return false;
  }
  renderer_ = std::make_unique<WorldRenderer>();
  if (!renderer_->initialize()) {
    error = "cannot compile the shaders: " + renderer_->log();
    renderer_.reset();
    return false;
  }
  renderer_->setSession(info);
  size_ = size;
  return true;
}

QImage OffscreenRenderer::render(const WorldSnapshot& snap, const OrbitCamera& camera) {
  context_.makeCurrent(&surface_);
  QOpenGLFramebufferObjectFormat format;
  format.setAttachment(QOpenGLFramebufferObject::Depth);
  format.setSamples(4);
  QOpenGLFramebufferObject fbo(size_, format);
  if (!fbo.isValid()) return {};
  fbo.bind();
  renderer_->upload(snap);
  renderer_->setHighlight(snap.selected.id, 0xFFFFFFFFu);
  renderer_->render(camera, size_.width(), size_.height());
  QImage image = fbo.toImage();
  fbo.release();
  return image;
}

double OffscreenRenderer::timeFrames(const WorldSnapshot& snap, const OrbitCamera& camera, int frames) {
  context_.makeCurrent(&surface_);
  QOpenGLFramebufferObjectFormat format;
  format.setAttachment(QOpenGLFramebufferObject::Depth);
  QOpenGLFramebufferObject fbo(size_, format);
  fbo.bind();
  renderer_->upload(snap, true);
  renderer_->render(camera, size_.width(), size_.height());  // warm-up: shader compilation
  context_.functions()->glFinish();
  QElapsedTimer timer;
  timer.start();
  for (int i = 0; i < frames; ++i) {
    renderer_->upload(snap, true);
    renderer_->render(camera, size_.width(), size_.height());
    context_.functions()->glFinish();
  }
  fbo.release();
  return double(timer.nsecsElapsed()) / 1e6 / std::max(frames, 1);
}

}  // namespace ide
