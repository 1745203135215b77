// Rendering snapshots without a window: an offscreen surface and framebuffer objects, for
// `vsim-ide --screenshot`, frame export (`--frames`) and measuring frame times.
#pragma once

#include <QImage>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QSize>
#include <QString>
#include <memory>

#include "orbit_camera.hpp"
#include "session_info.hpp"
#include "snapshot.hpp"

namespace ide {

class WorldRenderer;

class OffscreenRenderer {
 public:
  OffscreenRenderer();
  ~OffscreenRenderer();
  // Makes the context (OpenGL 3.3 core) and the renderer for pictures of `size` pixels; false
  // with `error` when the platform has none (then nothing else may be called).
  bool initialize(const SessionInfo& info, QSize size, QString& error);
  // The world as the 3D view draws it from `camera` (smooth edges: 4 samples per pixel); a null
  // image when the framebuffer cannot be made.
  QImage render(const WorldSnapshot& snap, const OrbitCamera& camera);
  // Draws `frames` frames as the window does while running (the blocks uploaded, then drawn, no
  // multisampling), each finished with glFinish; their mean wall time in ms.
  double timeFrames(const WorldSnapshot& snap, const OrbitCamera& camera, int frames);

 private:
  QOpenGLContext context_;
  QOffscreenSurface surface_;
  std::unique_ptr<WorldRenderer> renderer_;
  QSize size_;
};

// The camera the 3D view starts with: the world's <camera>, else a view of all blocks.
OrbitCamera initialCamera(const SessionInfo& info, const WorldSnapshot& snap);

}  // namespace ide
