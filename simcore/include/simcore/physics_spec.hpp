// What a world says of its mobiles and obstacles, and the constants of the air-jet model
// (physics.hpp), without the physics itself (no Eigen here: world files include this).
#pragma once

#include "simcore/time.hpp"

namespace simcore {

struct MobileSpec {
  double xMm = 0, yMm = 0, angleDeg = 0;  // centre and orientation
  double lxMm = 50, lyMm = 50;            // footprint
  double massKg = 0.02;
};

struct ObstacleSpec {  // an axis-aligned rectangle the mobiles cannot enter
  double xMm = 0, yMm = 0, lxMm = 25, lyMm = 25;
};

struct AirJetModel {
  double maxForceN = 0.005;       // one jet at full power, under the mobile
  double reachMm = 25;            // one Smart Block: beyond, a jet misses the mobile
  double riseTimeS = 0.010;       // the valve's time constant
  double dampingNsPerM = 0.05;    // c: the air cushion's viscous drag
  double angularDampingNms = 2e-5;  // c_theta, per radian per second
  SimTime step = kMillisecond;    // the Euler step
};

}  // namespace simcore
