// What the kernel needs to know about a kind of robot. Targets (targets/) fill one in; the kernel
// knows nothing else about them.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simcore/lattice.hpp"
#include "simcore/time.hpp"

namespace simcore {

class MotionRule;  // simcore/motion_rule.hpp

struct LinkModel {
  double rateBitsPerSecond = 1e6;  // transmission time = size * 8 / rate
  SimTime latency = 0;             // added after transmission
  SimTime jitter = 0;              // uniform extra delay in [0, jitter]; never reorders a link
};

// What the reality checker (stability.hpp) needs of a target that stands on a floor (z = 0) under
// gravity (-z). The figures are assumptions stated per target (targets/README.md): no published
// measurement of link strength exists for these modules.
struct GravityModel {
  bool applies = false;        // Smart Blocks lie on a table: no
  double blockMassKg = 0;      // every block the same
  double linkStrengthN = 0;    // the largest force one link carries before it lets go
  double linkLeverMm = 0;      // width of a link's contact: the arm of the couple that resists a moment
  bool flatBottom = false;     // cubes stand on their bottom square; spheres and discs on a point
};

enum class BodyShape { Cube, Sphere };

struct TargetSpec {
  std::string name;  // "blinkyblocks", "smartblocks", "catoms2d", "catoms3d"
  std::function<std::unique_ptr<Lattice>()> makeLattice;
  std::vector<std::string> faceNames;  // index = face number
  LinkModel link;
  // How move(face) moves a block: `motionRule` when set (e.g. the Catoms 2D roll around a pivot);
  // otherwise canTranslate selects a translation to the adjacent free cell through the face;
  // neither: move() answers VS_ERR_UNSUPPORTED. Rules are stateless, so targets can share one.
  bool canTranslate = false;
  std::shared_ptr<const MotionRule> motionRule;
  SimTime motionDuration = kSecond;
  bool hasTap = false;
  bool hasAccelerometer = false;
  bool hasDisplayValue = false;
  double blockSizeMm = 40.0;
  BodyShape shape = BodyShape::Cube;  // how renderers draw a block (cube of the size, or ball)
  GravityModel gravity;
  // Simulated computing time of one step of a block program on the block's processor: an
  // assumption per target that interpreted programs charge per step (the Meld VM: per rule
  // firing). vsim --time-per-rule overrides it.
  SimTime programStepTime = 1000;
  std::uint32_t defaultColor = 0x808080;

  bool canMove() const { return canTranslate || motionRule != nullptr; }
};

}  // namespace simcore
