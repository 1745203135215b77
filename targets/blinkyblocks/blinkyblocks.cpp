#include "blinkyblocks/blinkyblocks.hpp"

namespace targets {

simcore::TargetSpec blinkyBlocksTarget() {
  simcore::TargetSpec t;
  t.name = "blinkyblocks";
  t.makeLattice = [] {
    // x to the right, y to the back, z up.
    return std::make_unique<simcore::RegularLattice>(
        "cubic",
        std::vector<simcore::Cell>{{0, 0, -1}, {0, 1, 0}, {1, 0, 0}, {0, -1, 0}, {-1, 0, 0}, {0, 0, 1}},
        /*planar=*/false);
  };
  t.faceNames = {"bottom", "back", "right", "front", "left", "top"};
  // The real blocks talk over asynchronous serial lines between neighboring faces. We model them at
  // 38.4 kbit/s with no extra latency; both can be overridden per run.
  t.link.rateBitsPerSecond = 38400;
  t.canTranslate = false;
  t.programStepTime = 10 * 1000;  // assumed for an 8-bit 32 MHz microcontroller
  t.hasTap = true;
  t.hasAccelerometer = true;
  t.blockSizeMm = 40.0;
  // Under gravity: 40 mm cubes of an assumed 60 g, standing on their bottom face. Link strength
  // assumed 2.5 N (4.2 block weights): a block holds two blocks out on one side, not three (the
  // reality checker's model, stability.hpp; the VisibleSim paper's Fig. 6a case).
  t.gravity = {true, 0.060, 2.5, 40.0, true};
  t.defaultColor = 0x808080;
  return t;
}

}  // namespace targets
