#include "simcore/motion_rule.hpp"

#include <algorithm>
#include <cmath>

namespace simcore {

Vec3 motionPoint(const Vec3& from, const Vec3& to, const Vec3* pivot, double f) {
  const Vec3 chord{from.x + (to.x - from.x) * f, from.y + (to.y - from.y) * f, from.z + (to.z - from.z) * f};
  if (!pivot) return chord;
  // Spherical interpolation of the two radius vectors: the block's centre stays on the circle
  // around the pivot's centre, in the plane of the two radii.
  const Vec3 u{from.x - pivot->x, from.y - pivot->y, from.z - pivot->z};
  const Vec3 w{to.x - pivot->x, to.y - pivot->y, to.z - pivot->z};
  const double lu = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
  const double lw = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
  if (lu < 1e-12 || lw < 1e-12) return chord;
  const double c = std::clamp((u.x * w.x + u.y * w.y + u.z * w.z) / (lu * lw), -1.0, 1.0);
  const double theta = std::acos(c);
  const double s = std::sin(theta);
  if (s < 1e-9) return chord;  // no turn (or a half turn, whose plane is undefined): go straight
  const double a = std::sin((1 - f) * theta) / s, b = std::sin(f * theta) / s;
  // Unit radii interpolated, then scaled by the interpolated radius (equal radii in practice).
  const double r = lu + (lw - lu) * f;
  return Vec3{pivot->x + r * (a * u.x / lu + b * w.x / lw), pivot->y + r * (a * u.y / lu + b * w.y / lw),
              pivot->z + r * (a * u.z / lu + b * w.z / lw)};
}

}  // namespace simcore
