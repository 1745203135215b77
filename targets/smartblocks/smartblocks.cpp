#include "smartblocks/smartblocks.hpp"

namespace targets {

simcore::TargetSpec smartBlocksTarget() {
  simcore::TargetSpec t;
  t.name = "smartblocks";
  t.makeLattice = [] {
    return std::make_unique<simcore::RegularLattice>(
        "square", std::vector<simcore::Cell>{{0, 1, 0}, {1, 0, 0}, {0, -1, 0}, {-1, 0, 0}}, /*planar=*/true);
  };
  t.faceNames = {"north", "east", "south", "west"};
  t.link.rateBitsPerSecond = 1e6;
  t.canTranslate = true;
  t.programStepTime = 10 * 1000;  // assumed for a small microcontroller
  t.motionDuration = simcore::kSecond;
  t.hasDisplayValue = true;
  t.blockSizeMm = 25.0;
  t.defaultColor = 0x4080FF;
  return t;
}

}  // namespace targets
