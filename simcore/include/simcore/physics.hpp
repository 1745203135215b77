// Air-jet conveying on a Smart Blocks surface: mobiles (thin parallelepipeds lying on the blocks)
// pushed by the blocks' air jets, and obstacles (fixed rectangles).
//
// The model, after the VisibleSim paper's Eqs. 2 and 3 and the pneumatic actuator it cites, with
// our own constants (AirJetModel):
//   * Each block has one inclined jet per face. A jet blowing towards face d with commanded power
//     p in [0, 1] acts on a mobile whose footprint is within `reachMm` of the block's centre: the
//     force F = Fmax * p_eff * f1(r) * d, applied at the footprint's point nearest to the jet, with
//       f1(r) = 1 - r / reach            (r: distance from the jet to the footprint; 1 under it),
//     and p_eff following the command with the valve's first-order lag (the actuator's f2):
//       dp_eff/dt = (p - p_eff) / riseTime.
//   * The air cushion damps the motion: a force -c v and a torque -c_theta omega (Eq. 3).
//   * m dv/dt = sum F - c v;  I domega/dt = sum (q - x) x F - c_theta omega, with
//     I = m (lx^2 + ly^2) / 12, integrated by explicit Euler at a fixed step, run by the event
//     kernel only while a mobile moves or a jet blows. Same inputs, same steps, same trajectory.
//   * A step that would make a mobile overlap an obstacle is undone and the mobile stopped (a
//     plastic contact). Mobiles do not collide with each other.
// Positions are in mm on the surface (x east, y north, the blocks' centres at cell * block size),
// angles in degrees counter-clockwise; internally SI units.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "simcore/physics_spec.hpp"
#include "simcore/time.hpp"

namespace simcore {

struct MobileState {
  Eigen::Vector2d position{0, 0}, velocity{0, 0};  // m, m/s
  double angle = 0, angularVelocity = 0;            // rad, rad/s
};

// A block's jets and the mobiles; the kernel calls step() at fixed intervals while active().
class Physics {
 public:
  // `blockCentresMm`: the centre of every block on the surface, by block id.
  Physics(std::vector<Eigen::Vector2d> blockCentresMm, std::vector<MobileSpec> mobiles,
          std::vector<ObstacleSpec> obstacles, AirJetModel model);

  const AirJetModel& model() const { return model_; }
  std::size_t mobileCount() const { return mobiles_.size(); }
  const MobileState& mobile(std::size_t i) const { return state_[i]; }
  const MobileSpec& spec(std::size_t i) const { return mobiles_[i]; }
  const std::vector<ObstacleSpec>& obstacles() const { return obstacles_; }
  // Position in mm and angle in degrees.
  Eigen::Vector2d positionMm(std::size_t i) const { return state_[i].position * 1000.0; }
  double angleDeg(std::size_t i) const;

  // Commands block b's jet towards `direction` (a unit vector on the surface: its face's) at power
  // p (clamped to [0, 1]) until `until`; a new command replaces the jet's previous one.
  void setJet(std::uint32_t block, int face, const Eigen::Vector2d& direction, double power, SimTime until);

  // One Euler step of model().step from `now`. Returns whether to go on (a mobile moves, or a jet
  // blows or has not died down).
  bool step(SimTime now);
  bool active() const;

  // The mobile whose footprint covers block b's centre (-1: none), as of the last step.
  int mobileOver(std::uint32_t block) const;
  // Blocks whose coverage changed in the last step: (block, mobile, arrived or left).
  struct CoverChange {
    std::uint32_t block;
    int mobile;
    bool arrived;
  };
  const std::vector<CoverChange>& coverChanges() const { return changes_; }
  // Recomputes coverage from the current positions (at the start, before any step).
  void updateCoverage();

 private:
  struct Jet {
    std::uint32_t block;
    int face;
    Eigen::Vector2d direction;
    double command, effective;
    SimTime until;
  };
  Eigen::Vector2d corner(std::size_t i, int k) const;  // footprint corners, m
  bool covers(std::size_t i, const Eigen::Vector2d& pointM) const;
  Eigen::Vector2d nearestOnFootprint(std::size_t i, const Eigen::Vector2d& pointM) const;
  bool overlapsObstacle(std::size_t i) const;

  std::vector<Eigen::Vector2d> blocks_;  // centres, m
  std::vector<MobileSpec> mobiles_;
  std::vector<ObstacleSpec> obstacles_;
  AirJetModel model_;
  std::vector<MobileState> state_;
  std::vector<Jet> jets_;           // the jets blowing or dying down; few at a time
  std::vector<int> over_;           // per block: the mobile covering it, -1
  std::vector<CoverChange> changes_;
};

}  // namespace simcore
