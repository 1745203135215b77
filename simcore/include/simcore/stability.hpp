// The reality checker: does a configuration of blocks standing on a floor (z = 0) under gravity
// hold? Two questions, as the VisibleSim paper asks them:
//
// (a) Links. Blocks are ranked by their number of links from the floor; each block not on the
//     floor is carried by its neighbors one rank lower, in equal shares (a ball resting on four
//     balls by each of them, a block at the end of an arm by the one before it), and passes what it
//     carries on the same way. A link then holds a load: W, the weight of its share of what hangs
//     from it, and G, that load's centre of mass. With n the unit vector from the carrier to the
//     held block (n_z its vertical part), q the centre of their contact, r the horizontal distance
//     from q to G and a the width of the contact (GravityModel::linkLeverMm), the force the link
//     must carry is
//         F = W max(0, -n_z)              pulled out (the held block hangs below)
//           + W sqrt(1 - n_z^2)           sheared (it hangs beside)
//           + W r / a                     the moment, held by a couple across the contact ...
//             (W max(0, r - a/2) / a      ... or, for a block resting on its carrier (n_z > 0),
//                                         only once G leaves the contact: until then it rests)
//     A link is overloaded when F exceeds the target's strength (GravityModel::linkStrengthN).
//     Equal shares are a simplification (a stiff structure shares by stiffness, not by count).
// (b) Balance. Each connected structure must touch the floor, and the vertical through its centre
//     of mass must meet the convex hull of its floor contacts (the bottom squares of cubes, the
//     points where spheres touch); if not, it tips about the part of that hull nearest to the
//     centre of mass: an edge (the pivot axis) or a corner.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <vector>

#include "simcore/lattice.hpp"
#include "simcore/motion_rule.hpp"
#include "simcore/target_spec.hpp"
#include "simcore/world.hpp"

namespace simcore {

class Simulation;

struct FallingStructure {  // no block on the floor
  std::vector<BlockId> blocks;
};

struct TippingStructure {
  std::vector<BlockId> blocks;
  Vec3 centreOfMassMm;
  Vec3 pivotFromMm, pivotToMm;     // the axis it tips about, on the floor (equal: a corner)
  std::vector<BlockId> pivotBlocks;  // the floor blocks touching that axis
};

struct OverloadedLink {
  BlockId carrier, held;
  int face;           // of the carrier
  double forceN;      // what it must carry
  double hanging;      // the load, in blocks' weight
};

struct StabilityReport {
  std::size_t blocks = 0, structures = 0, loadedLinks = 0;
  double maxLinkForceN = 0, linkStrengthN = 0;
  std::vector<FallingStructure> falling;
  std::vector<TippingStructure> tipping;
  std::vector<OverloadedLink> overloaded;
  bool stable() const { return falling.empty() && tipping.empty() && overloaded.empty(); }
};

// A block considered elsewhere than where it is (a motion about to start).
struct MovedBlock {
  BlockId id;
  Cell to;
};

// Checks every alive block at its cell (a moving block at its destination; `moved` at its cell).
// Throws std::invalid_argument for a target without a gravity model.
StabilityReport checkStability(const World& world, const TargetSpec& target, const MovedBlock* moved = nullptr);

// "stability: stable (...)" or "stability: unstable (...)" and a line per problem.
void printStability(std::ostream& out, const StabilityReport& report, const TargetSpec& target);

// Checks the result of every motion before it starts: an unstable one is reported to `out` and,
// when `refuse`, refused with VS_ERR_UNSTABLE.
class StabilityGuard final : public MotionCheck {
 public:
  StabilityGuard(std::ostream* out, bool refuse) : out_(out), refuse_(refuse) {}
  int check(const Simulation& sim, BlockId id, const Cell& to) override;
  std::size_t checked() const { return checked_; }
  std::size_t unstable() const { return unstable_; }

 private:
  std::ostream* out_;
  bool refuse_;
  std::size_t checked_ = 0, unstable_ = 0;
};

}  // namespace simcore
