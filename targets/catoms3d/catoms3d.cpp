#include "catoms3d/catoms3d.hpp"

#include <memory>

#include "catoms3d/fcc_lattice.hpp"
#include "catoms3d/rotation_rule.hpp"

namespace targets {

simcore::TargetSpec catoms3DTarget() {
  simcore::TargetSpec t;
  t.name = "catoms3d";
  t.makeLattice = [] { return std::make_unique<FccLattice>(); };
  t.faceNames = {"side0", "side1", "top2",    "top3",    "top4",     "top5",
                 "side6", "side7", "bottom8", "bottom9", "bottom10", "bottom11"};
  // Connectors talk to the module they touch. No measured figure is published for the prototypes;
  // we use 1 Mbit/s and no extra latency, like Catoms 2D, both overridable per run.
  t.link.rateBitsPerSecond = 1e6;
  t.link.latency = 0;
  // Rotations over a neighbor's surface with the published blocking rules (rotation_rule.hpp).
  t.motionRule = std::make_shared<FccRotationRule>();
  // VisibleSim lets the user tap any module; there is no accelerometer and no display.
  t.hasTap = true;
  t.blockSizeMm = 10.0;  // VisibleSim's Catoms 3D worlds use blockSize="10,10,10"
  t.shape = simcore::BodyShape::Sphere;
  // Under gravity: an assumed 30 g per catom, resting on a point of the floor; a link's connector
  // is taken as half a diameter wide, with an assumed strength of 1.25 N (4.2 catom weights).
  t.gravity = {true, 0.030, 1.25, 5.0, false};
  t.defaultColor = 0x808080;
  return t;
}

}  // namespace targets
