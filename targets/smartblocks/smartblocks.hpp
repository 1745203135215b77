// Smart Blocks: 25 mm square blocks on a 2D square lattice, 4 faces, translation to an adjacent free
// cell (1 s by default), and a displayed value.
#pragma once

#include "simcore/target_spec.hpp"

namespace targets {

// Face numbers as in the Smart Blocks Meld include file: north=0, east=1, south=2, west=3.
enum SmartFace { kSBNorth = 0, kSBEast = 1, kSBSouth = 2, kSBWest = 3 };

simcore::TargetSpec smartBlocksTarget();

}  // namespace targets
