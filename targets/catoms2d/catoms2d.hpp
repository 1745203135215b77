// Catoms 2D: disk-shaped modules on a hexagonal lattice in the x–z plane (hex_lattice.hpp), 6 faces,
// an RGB LED, and a 60-degree roll around a neighbor (rotation_rule.hpp), 1 s by default.
#pragma once

#include "simcore/target_spec.hpp"

namespace targets {

// Face numbers as in the Catoms 2D Meld include file (C2D.meld): counter-clockwise from the right.
enum Catoms2DFace {
  kC2DRight = 0,
  kC2DTopRight = 1,
  kC2DTopLeft = 2,
  kC2DLeft = 3,
  kC2DBottomLeft = 4,
  kC2DBottomRight = 5
};

simcore::TargetSpec catoms2DTarget();

}  // namespace targets
