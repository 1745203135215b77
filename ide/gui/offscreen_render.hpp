// Rendering a snapshot without a window: an offscreen surface and a framebuffer object, for
// `vsim-ide --screenshot` and for measuring frame times.
#pragma once

#include <QImage>
#include <QSize>
#include <QString>

#include "orbit_camera.hpp"
#include "session_info.hpp"
#include "snapshot.hpp"

namespace ide {

// The world as the 3D view draws it from `camera`, `size` pixels; null image and `error` set
// when no OpenGL 3.3 context can be made. `frameTimes` > 0 draws that many more frames first
// and stores their mean wall time in ms (each frame finished with glFinish) in `msPerFrame`.
QImage renderOffscreen(const SessionInfo& info, const WorldSnapshot& snap, const OrbitCamera& camera,
                       QSize size, QString& error, int frameTimes = 0, double* msPerFrame = nullptr);

// The camera the 3D view starts with: the world's <camera>, else a view of all blocks.
OrbitCamera initialCamera(const SessionInfo& info, const WorldSnapshot& snap);

}  // namespace ide
