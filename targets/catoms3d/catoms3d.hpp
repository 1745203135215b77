// Catoms 3D: quasi-spherical modules on a face-centred cubic lattice (fcc_lattice.hpp), 12
// connectors, an RGB LED. move(face) rotates the catom over a neighbor's surface into the cell behind
// `face` (rotation_rule.hpp).
#pragma once

#include "simcore/target_spec.hpp"

namespace targets {

// Connector numbers as in the Catoms 3D Meld include file (C3D.meld).
enum Catoms3DFace {
  kC3DSide0 = 0,
  kC3DSide1 = 1,
  kC3DTop2 = 2,
  kC3DTop3 = 3,
  kC3DTop4 = 4,
  kC3DTop5 = 5,
  kC3DSide6 = 6,
  kC3DSide7 = 7,
  kC3DBottom8 = 8,
  kC3DBottom9 = 9,
  kC3DBottom10 = 10,
  kC3DBottom11 = 11
};

simcore::TargetSpec catoms3DTarget();

}  // namespace targets
