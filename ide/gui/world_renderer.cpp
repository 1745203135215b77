#include "world_renderer.hpp"

#include <QtMath>
#include <algorithm>
#include <cmath>

#include "block_meshes.hpp"

namespace ide {

namespace {

const char* kBlockVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 iPosition;
layout(location = 3) in vec4 iColor;
layout(location = 4) in float iFlags;
uniform mat4 uViewProjection;
uniform vec3 uScale;
out vec3 vNormal;
out vec3 vWorld;
out vec3 vColor;
flat out float vFlags;
void main() {
  // The selected block is drawn a little larger, so that its rim shows around it.
  vec3 world = iPosition + aPosition * uScale * (iFlags > 0.5 && iFlags < 1.5 ? 1.12 : 1.0);
  vNormal = normalize(aNormal / uScale);
  vWorld = world;
  vColor = iColor.rgb;
  vFlags = iFlags;
  gl_Position = uViewProjection * vec4(world, 1.0);
}
)";

// Lambert lighting from the world's spotlight (full inside its cone, fading over a few degrees
// outside), a dim fill light so that nothing is black, and a rim for the selected and hovered
// blocks.
const char* kBlockFragment = R"(#version 330 core
in vec3 vNormal;
in vec3 vWorld;
in vec3 vColor;
flat in float vFlags;
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;
uniform float uLightCosCutoff;
uniform vec3 uEye;
out vec4 fragColor;
void main() {
  vec3 n = normalize(vNormal);
  vec3 toLight = normalize(uLightPosition - vWorld);
  float cone = smoothstep(uLightCosCutoff - 0.05, uLightCosCutoff, dot(-toLight, uLightDirection));
  float diffuse = max(dot(n, toLight), 0.0) * mix(0.35, 1.0, cone);
  float fill = 0.25 + 0.15 * max(n.z, 0.0);
  vec3 color = vColor * min(fill + 0.75 * diffuse, 1.15);
  vec3 toEye = normalize(uEye - vWorld);
  float rim = pow(1.0 - max(dot(n, toEye), 0.0), 2.0);
  if (vFlags > 1.5) {
    color = mix(color, vec3(1.0), 0.25 + 0.5 * rim);
  } else if (vFlags > 0.5) {
    // A rim that contrasts with the block's own colour: dark on light blocks, white on dark ones.
    float luminance = dot(vColor, vec3(0.3, 0.59, 0.11));
    vec3 rimColor = luminance > 0.5 ? vec3(0.05) : vec3(1.0);
    color = mix(color, rimColor, clamp(0.4 + 1.6 * rim, 0.0, 0.9));
  }
  fragColor = vec4(color, 1.0);
}
)";

const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
void main() { gl_Position = uViewProjection * vec4(aPosition, 1.0); }
)";

const char* kLineFragment = R"(#version 330 core
uniform vec4 uColor;
out vec4 fragColor;
void main() { fragColor = uColor; }
)";

QVector3D fromSpherical(const ViewPoint& v) {
  const float theta = qDegreesToRadians(v.thetaDeg), phi = qDegreesToRadians(v.phiDeg);
  return QVector3D(v.target[0], v.target[1], v.target[2]) +
         v.distance *
             QVector3D(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
}

std::uint32_t rgba(std::uint32_t rgb) {
  // Bytes R, G, B, A in memory order for GL_UNSIGNED_BYTE.
  return ((rgb >> 16) & 0xFF) | (rgb & 0xFF00) | ((rgb & 0xFF) << 16) | 0xFF000000u;
}

}  // namespace

WorldRenderer::WorldRenderer() = default;
WorldRenderer::~WorldRenderer() = default;

bool WorldRenderer::initialize() {
  initializeOpenGLFunctions();
  bool ok = blocks_.addShaderFromSourceCode(QOpenGLShader::Vertex, kBlockVertex) &&
            blocks_.addShaderFromSourceCode(QOpenGLShader::Fragment, kBlockFragment) && blocks_.link();
  ok = ok && lines_.addShaderFromSourceCode(QOpenGLShader::Vertex, kLineVertex) &&
       lines_.addShaderFromSourceCode(QOpenGLShader::Fragment, kLineFragment) && lines_.link();
  if (!ok) {
    log_ = blocks_.log() + lines_.log();
    return false;
  }
  blockVao_.create();
  floorVao_.create();
  meshVbo_.create();
  meshIbo_.create();
  instanceVbo_.create();
  floorVbo_.create();
  instanceVbo_.setUsagePattern(QOpenGLBuffer::StreamDraw);

  blockVao_.bind();
  meshVbo_.bind();
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<void*>(offsetof(MeshVertex, normal)));
  instanceVbo_.bind();
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(Instance), nullptr);
  glVertexAttribDivisor(2, 1);
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Instance),
                        reinterpret_cast<void*>(offsetof(Instance, color)));
  glVertexAttribDivisor(3, 1);
  glEnableVertexAttribArray(4);
  glVertexAttribPointer(4, 1, GL_FLOAT, GL_FALSE, sizeof(Instance),
                        reinterpret_cast<void*>(offsetof(Instance, flags)));
  glVertexAttribDivisor(4, 1);
  blockVao_.release();

  floorVao_.bind();
  floorVbo_.bind();
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  floorVao_.release();
  ready_ = true;
  return true;
}

void WorldRenderer::setSession(const SessionInfo& info) {
  info_ = info;
  const Mesh mesh = blockMesh(info.shape);
  meshIndices_ = int(mesh.indices.size());
  blockVao_.bind();  // the index buffer binding belongs to the vertex array
  meshVbo_.bind();
  meshVbo_.allocate(mesh.vertices.data(), int(mesh.vertices.size() * sizeof(MeshVertex)));
  meshIbo_.bind();
  meshIbo_.allocate(mesh.indices.data(), int(mesh.indices.size() * sizeof(std::uint16_t)));
  blockVao_.release();
  buildFloor(info);
  uploadedSerial_ = 0;
  instances_ = 0;
}

void WorldRenderer::buildFloor(const SessionInfo& info) {
  // One line per cell boundary across the grid's x-y extent, at z = 0 under the lowest layer.
  const float sx = info.blockSizeMm[0], sy = info.blockSizeMm[1];
  const float z = -0.001f * info.blockSizeMm[2];
  const int nx = std::min(info.grid.x, 2000), ny = std::min(info.grid.y, 2000);
  std::vector<float> v;
  v.reserve(std::size_t(nx + ny + 2) * 6);
  const float x0 = 0, x1 = float(nx) * sx, y0 = 0, y1 = float(ny) * sy;
  for (int i = 0; i <= nx; ++i) {
    const float x = x0 + float(i) * sx;
    v.insert(v.end(), {x, y0, z, x, y1, z});
  }
  for (int j = 0; j <= ny; ++j) {
    const float y = y0 + float(j) * sy;
    v.insert(v.end(), {x0, y, z, x1, y, z});
  }
  floorVertices_ = int(v.size() / 3);
  floorVbo_.bind();
  floorVbo_.allocate(v.data(), int(v.size() * sizeof(float)));
}

void WorldRenderer::upload(const WorldSnapshot& snap, bool force) {
  if (!force && snap.session == uploadedSession_ && snap.serial == uploadedSerial_) return;
  uploadedSession_ = snap.session;
  uploadedSerial_ = snap.serial;
  staging_.clear();
  instanceBlock_.clear();
  staging_.reserve(snap.positions.size());
  for (std::size_t b = 0; b < snap.positions.size(); ++b) {
    if (!snap.alive[b]) continue;
    const auto& p = snap.positions[b];
    staging_.push_back(Instance{{p[0], p[1], p[2]}, rgba(snap.colors[b]), 0.0f});
    instanceBlock_.push_back(std::uint32_t(b));
  }
  uploadInstances();
}

void WorldRenderer::setHighlight(std::uint32_t selected, std::uint32_t hovered) {
  if (selected == selected_ && hovered == hovered_) return;
  selected_ = selected;
  hovered_ = hovered;
  uploadInstances();
}

void WorldRenderer::uploadInstances() {
  for (std::size_t i = 0; i < staging_.size(); ++i) {
    const std::uint32_t b = instanceBlock_[i];
    staging_[i].flags = b == selected_ ? 1.0f : b == hovered_ ? 2.0f : 0.0f;
  }
  instances_ = staging_.size();
  if (!ready_) return;
  instanceVbo_.bind();
  // Orphan the old storage, so the driver need not wait for draws that still read it.
  instanceVbo_.allocate(int(staging_.size() * sizeof(Instance)));
  if (!staging_.empty()) instanceVbo_.write(0, staging_.data(), int(staging_.size() * sizeof(Instance)));
}

void WorldRenderer::render(const OrbitCamera& camera, int width, int height) {
  glViewport(0, 0, width, height);
  glClearColor(0.80f, 0.84f, 0.88f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  const QMatrix4x4 viewProjection =
      camera.projection(float(width) / float(std::max(height, 1))) * camera.view();
  drawFloor(viewProjection);
  if (instances_ == 0 || meshIndices_ == 0) return;

  ViewPoint light;
  if (info_.spotlight) {
    light = *info_.spotlight;
  } else {  // over the camera's target, from above and a little to the side
    light = camera.viewPoint();
    light.thetaDeg -= 30;
    light.phiDeg = 60;
    light.distance *= 1.5f;
    light.angleDeg = 90;
  }
  const QVector3D lightPosition = fromSpherical(light);
  const QVector3D lightTarget(light.target[0], light.target[1], light.target[2]);
  blocks_.bind();
  blocks_.setUniformValue("uViewProjection", viewProjection);
  blocks_.setUniformValue("uScale",
                          QVector3D(info_.blockSizeMm[0], info_.blockSizeMm[1], info_.blockSizeMm[2]));
  blocks_.setUniformValue("uLightPosition", lightPosition);
  blocks_.setUniformValue("uLightDirection", (lightTarget - lightPosition).normalized());
  blocks_.setUniformValue("uLightCosCutoff", std::cos(qDegreesToRadians(std::min(light.angleDeg, 89.0f))));
  blocks_.setUniformValue("uEye", camera.eye());
  blockVao_.bind();
  glDrawElementsInstanced(GL_TRIANGLES, meshIndices_, GL_UNSIGNED_SHORT, nullptr, GLsizei(instances_));
  blockVao_.release();
  blocks_.release();
}

void WorldRenderer::drawFloor(const QMatrix4x4& viewProjection) {
  if (floorVertices_ == 0) return;
  lines_.bind();
  lines_.setUniformValue("uViewProjection", viewProjection);
  lines_.setUniformValue("uColor", QVector4D(0.55f, 0.58f, 0.62f, 1.0f));
  floorVao_.bind();
  glDrawArrays(GL_LINES, 0, floorVertices_);
  floorVao_.release();
  lines_.release();
}

}  // namespace ide
