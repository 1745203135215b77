// Blinky Blocks: 40 mm cubes on a cubic lattice, 6 faces, an RGB LED, tap and accelerometer; no motion.
#pragma once

#include "simcore/target_spec.hpp"

namespace targets {

// Face numbers as in the Blinky Blocks Meld include file: bottom=0, back=1, right=2, front=3, left=4, top=5.
enum BlinkyFace { kBBBottom = 0, kBBBack = 1, kBBRight = 2, kBBFront = 3, kBBLeft = 4, kBBTop = 5 };

simcore::TargetSpec blinkyBlocksTarget();

}  // namespace targets
