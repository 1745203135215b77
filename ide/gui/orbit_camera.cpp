#include "orbit_camera.hpp"

#include <QtMath>
#include <algorithm>
#include <cmath>
#include <limits>

namespace ide {

void OrbitCamera::set(const ViewPoint& v) {
  view_ = v;
  view_.phiDeg = std::clamp(view_.phiDeg, -89.0f, 89.0f);
  view_.angleDeg = std::clamp(view_.angleDeg, 5.0f, 120.0f);
}

void OrbitCamera::frame(const QVector3D& lo, const QVector3D& hi) {
  const QVector3D c = (lo + hi) * 0.5f;
  const float radius = std::max(1.0f, (hi - lo).length() * 0.5f);
  ViewPoint v;
  v.target = {c.x(), c.y(), c.z()};
  v.thetaDeg = 45;
  v.phiDeg = 35;
  v.angleDeg = 45;
  v.distance = radius / std::sin(qDegreesToRadians(v.angleDeg * 0.5f)) * 1.05f;
  set(v);
}

void OrbitCamera::orbit(float dThetaDeg, float dPhiDeg) {
  view_.thetaDeg = std::fmod(view_.thetaDeg + dThetaDeg, 360.0f);
  view_.phiDeg = std::clamp(view_.phiDeg + dPhiDeg, -89.0f, 89.0f);
}

void OrbitCamera::pan(float dx, float dy) {
  const QVector3D forward = (target() - eye()).normalized();
  QVector3D right = QVector3D::crossProduct(forward, QVector3D(0, 0, 1));
  if (right.lengthSquared() < 1e-6f) right = QVector3D(1, 0, 0);
  right.normalize();
  const QVector3D up = QVector3D::crossProduct(right, forward).normalized();
  const float height = 2.0f * view_.distance * std::tan(qDegreesToRadians(view_.angleDeg * 0.5f));
  focus(target() - right * (dx * height) - up * (dy * height));
}

void OrbitCamera::zoom(float factor) { view_.distance = std::clamp(view_.distance * factor, 1.0f, 1e8f); }

QVector3D OrbitCamera::eye() const {
  const float theta = qDegreesToRadians(view_.thetaDeg), phi = qDegreesToRadians(view_.phiDeg);
  const QVector3D dir(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
  return target() + dir * view_.distance;
}

QMatrix4x4 OrbitCamera::view() const {
  QMatrix4x4 m;
  m.lookAt(eye(), target(), QVector3D(0, 0, 1));
  return m;
}

QMatrix4x4 OrbitCamera::projection(float aspect) const {
  QMatrix4x4 m;
  m.perspective(view_.angleDeg, aspect, view_.distance * 0.01f, view_.distance * 20.0f);
  return m;
}

void OrbitCamera::ray(float x, float y, int w, int h, QVector3D& origin, QVector3D& direction) const {
  const QMatrix4x4 inverse = (projection(float(w) / float(std::max(h, 1))) * view()).inverted();
  const float nx = 2.0f * x / float(std::max(w, 1)) - 1.0f, ny = 1.0f - 2.0f * y / float(std::max(h, 1));
  const QVector3D nearPoint = inverse.map(QVector3D(nx, ny, -1.0f));
  const QVector3D farPoint = inverse.map(QVector3D(nx, ny, 1.0f));
  origin = nearPoint;
  direction = (farPoint - nearPoint).normalized();
}

std::uint32_t pickBlock(const QVector3D& origin, const QVector3D& direction,
                        const std::vector<std::array<float, 3>>& positions,
                        const std::vector<std::uint8_t>& alive, float radius) {
  std::uint32_t best = 0xFFFFFFFFu;
  float bestT = std::numeric_limits<float>::max();
  const float r2 = radius * radius;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!alive[i]) continue;
    const QVector3D toCentre = QVector3D(positions[i][0], positions[i][1], positions[i][2]) - origin;
    const float t = QVector3D::dotProduct(toCentre, direction);
    if (t <= 0) continue;
    const float d2 = toCentre.lengthSquared() - t * t;
    if (d2 > r2) continue;
    const float hit = t - std::sqrt(r2 - d2);
    if (hit < bestT) bestT = hit, best = std::uint32_t(i);
  }
  return best;
}

}  // namespace ide
