// Shared by the Catoms 2D tests: short names for the six faces and a tolerance comparison.
#pragma once

#include <cmath>

#include "catoms2d/catoms2d.hpp"

namespace c2dtest {

constexpr int kRight = targets::kC2DRight, kTopRight = targets::kC2DTopRight, kTopLeft = targets::kC2DTopLeft,
              kLeft = targets::kC2DLeft, kBottomLeft = targets::kC2DBottomLeft,
              kBottomRight = targets::kC2DBottomRight;

inline bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }

}  // namespace c2dtest
