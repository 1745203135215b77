// The 3D view's camera: it looks at a target from a direction given in spherical coordinates, as
// VisibleSim's <camera target=".." directionSpherical="theta,phi,distance" angle="fov"/> (z up).
// Orbit turns the direction, pan moves the target in the view plane, zoom scales the distance.
#pragma once

#include <QMatrix4x4>
#include <QVector3D>
#include <array>
#include <optional>
#include <vector>

#include "session_info.hpp"

namespace ide {

class OrbitCamera {
 public:
  void set(const ViewPoint& v);
  // A view of the whole box [lo, hi] (mm) from the usual VisibleSim angle.
  void frame(const QVector3D& lo, const QVector3D& hi);
  ViewPoint viewPoint() const { return view_; }

  void orbit(float dThetaDeg, float dPhiDeg);
  // Moves the target by a fraction of the visible height (dx right, dy up on screen).
  void pan(float dx, float dy);
  void zoom(float factor);
  void focus(const QVector3D& target) { view_.target = {target.x(), target.y(), target.z()}; }

  QVector3D eye() const;
  QVector3D target() const { return QVector3D(view_.target[0], view_.target[1], view_.target[2]); }
  QMatrix4x4 view() const;
  QMatrix4x4 projection(float aspect) const;
  // The ray through a pixel (x right, y down) of a viewport of w x h pixels.
  void ray(float x, float y, int w, int h, QVector3D& origin, QVector3D& direction) const;

 private:
  ViewPoint view_;
};

// The nearest block whose bounding sphere the ray hits, or kNoBlock (alive blocks only).
std::uint32_t pickBlock(const QVector3D& origin, const QVector3D& direction,
                        const std::vector<std::array<float, 3>>& positions,
                        const std::vector<std::uint8_t>& alive, float radius);

}  // namespace ide
