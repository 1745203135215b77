#include "offscreen_render.hpp"

#include <QElapsedTimer>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
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

QImage renderOffscreen(const SessionInfo& info, const WorldSnapshot& snap, const OrbitCamera& camera,
                       QSize size, QString& error, int frameTimes, double* msPerFrame) {
  QOpenGLContext context;
  context.setFormat(QSurfaceFormat::defaultFormat());
  if (!context.create()) {
    error = "cannot create an OpenGL context";
    return {};
  }
  QOffscreenSurface surface;
  surface.setFormat(context.format());
  surface.create();
  if (!context.makeCurrent(&surface)) {
    error = "cannot make the OpenGL context current on an offscreen surface";
    return {};
  }
  const QSurfaceFormat f = context.format();
  if (f.majorVersion() * 10 + f.minorVersion() < 33) {
    error =
        QString("OpenGL 3.3 is needed, the context has %1.%2").arg(f.majorVersion()).arg(f.minorVersion());
    return {};
  }
  QImage image;
  {
    WorldRenderer renderer;
    if (!renderer.initialize()) {
      error = "cannot compile the shaders: " + renderer.log();
      return {};
    }
    renderer.setSession(info);
    renderer.upload(snap);
    renderer.setHighlight(snap.selected.id, 0xFFFFFFFFu);
    QOpenGLFramebufferObjectFormat fboFormat;
    fboFormat.setAttachment(QOpenGLFramebufferObject::Depth);
    if (frameTimes > 0 && msPerFrame) {
      // Timed like the window draws: no multisampling.
      QOpenGLFramebufferObject fbo(size, fboFormat);
      fbo.bind();
      renderer.render(camera, size.width(), size.height());  // warm-up: shader compilation
      context.functions()->glFinish();
      QElapsedTimer timer;
      timer.start();
      for (int i = 0; i < frameTimes; ++i) {  // each frame as while running: upload, then draw
        renderer.upload(snap, true);
        renderer.render(camera, size.width(), size.height());
        context.functions()->glFinish();
      }
      *msPerFrame = double(timer.nsecsElapsed()) / 1e6 / frameTimes;
      fbo.release();
    }
    fboFormat.setSamples(4);  // the picture: smooth edges
    QOpenGLFramebufferObject fbo(size, fboFormat);
    if (!fbo.isValid()) {
      error = "cannot make a framebuffer of that size";
      return {};
    }
    fbo.bind();
    renderer.render(camera, size.width(), size.height());
    image = fbo.toImage();
    fbo.release();
  }
  context.doneCurrent();
  return image;
}

}  // namespace ide
