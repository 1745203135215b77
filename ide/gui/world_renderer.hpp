// Draws a world snapshot with OpenGL 3.3 core: every block in one instanced draw call (one mesh
// per target shape, per-instance position, colour and highlight), lit by the world's spotlight,
// over a floor grid. Needs a current context for every call; the 3D view widget and the headless
// screenshot both draw through it.
#pragma once

#include <QMatrix4x4>
#include <QOpenGLBuffer>
#include <QOpenGLExtraFunctions>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <cstdint>
#include <memory>

#include "orbit_camera.hpp"
#include "session_info.hpp"
#include "snapshot.hpp"

namespace ide {

class WorldRenderer : protected QOpenGLExtraFunctions {
 public:
  WorldRenderer();
  ~WorldRenderer();
  // Compiles the shaders; false (with log()) if the context cannot. Call once per context.
  bool initialize();
  const QString& log() const { return log_; }

  // A new session: mesh for its shape, floor for its grid.
  void setSession(const SessionInfo& info);
  // Uploads the blocks of a snapshot (only when it is newer than the last one uploaded, or forced).
  void upload(const WorldSnapshot& snap, bool force = false);
  void setHighlight(std::uint32_t selected, std::uint32_t hovered);
  void render(const OrbitCamera& camera, int width, int height);

  std::size_t instanceCount() const { return instances_; }

 private:
  struct Instance {
    float position[3];
    std::uint32_t color;  // RGBA bytes
    float flags;          // 1 = selected, 2 = hovered
  };
  void buildFloor(const SessionInfo& info);
  void drawFloor(const QMatrix4x4& viewProjection);
  void uploadInstances();

  QOpenGLShaderProgram blocks_, lines_;
  QOpenGLVertexArrayObject blockVao_, floorVao_;
  QOpenGLBuffer meshVbo_{QOpenGLBuffer::VertexBuffer}, meshIbo_{QOpenGLBuffer::IndexBuffer};
  QOpenGLBuffer instanceVbo_{QOpenGLBuffer::VertexBuffer};
  QOpenGLBuffer floorVbo_{QOpenGLBuffer::VertexBuffer};
  int meshIndices_ = 0, floorVertices_ = 0;
  std::vector<Instance> staging_;
  std::vector<std::uint32_t> instanceBlock_;  // block id of each instance
  std::size_t instances_ = 0;
  std::uint64_t uploadedSerial_ = 0, uploadedSession_ = 0;
  std::uint32_t selected_ = 0xFFFFFFFFu, hovered_ = 0xFFFFFFFFu;
  SessionInfo info_;
  QString log_;
  bool ready_ = false;
};

}  // namespace ide
