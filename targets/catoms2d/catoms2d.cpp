#include "catoms2d/catoms2d.hpp"

#include <memory>

#include "catoms2d/hex_lattice.hpp"
#include "catoms2d/rotation_rule.hpp"

namespace targets {

simcore::TargetSpec catoms2DTarget() {
  simcore::TargetSpec t;
  t.name = "catoms2d";
  t.makeLattice = [] { return std::make_unique<HexLattice>(); };
  t.faceNames = {"right", "top-right", "top-left", "left", "bottom-left", "bottom-right"};
  // Neighboring catoms talk through their contact faces. No measured figure is published for the
  // prototypes; we use the Smart Blocks' 1 Mbit/s and no extra latency, both overridable per run.
  t.link.rateBitsPerSecond = 1e6;
  t.link.latency = 0;
  t.motionRule = std::make_shared<const HexRotationRule>();
  t.motionDuration = simcore::kSecond;
  // VisibleSim lets the user tap any module; there is no accelerometer and no display.
  t.hasTap = true;
  t.blockSizeMm = 10.0;
  t.shape = simcore::BodyShape::Sphere;
  // Under gravity: an assumed 30 g per catom, resting on a point of the floor; a link's connector
  // is taken as half a diameter wide, with an assumed strength of 1.25 N (4.2 catom weights).
  t.gravity = {true, 0.030, 1.25, 5.0, false};
  t.defaultColor = 0x808080;
  return t;
}

}  // namespace targets
