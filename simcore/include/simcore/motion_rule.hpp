// How a target's blocks move. The block ABI's move(face) names the face a block wants to go
// through; a MotionRule decides whether that motion is legal here and now, where it ends and which
// cells it needs on the way. The kernel then reserves those cells, times the motion and keeps links
// and events consistent — so it knows no target: Smart Blocks slide, Catoms 2D roll around a pivot.
#pragma once

#include <cstdint>

#include "simcore/blockcode.h"
#include "simcore/lattice.hpp"
#include "simcore/world.hpp"

namespace simcore {

// The cells a motion needs besides its destination are named by faces of the block's origin cell
// and of its destination cell, as two bit masks: the kernel keeps four bytes for them per moving
// block (a million may move at once). That covers a roll around a neighbor (Catoms 2D: one cell
// beside the path) and a rotation over a neighbor's surface (Catoms 3D: cells next to either end).
inline constexpr int kMaxMotionFaces = 16;  // faces a swept-cell mask can name

struct MotionPlan {
  Cell to;  // the destination: reserved at once, settled when the motion ends
  // The cells behind these faces of the origin (bit f: face f) and of the destination are ones the
  // block passes through or next to: they must be free when the motion starts and stay reserved until
  // it ends, so no other block can enter them meanwhile.
  std::uint16_t sweptFromFaces = 0, sweptToFaces = 0;
  // The block turns around the centre of the cell behind this face of the origin (its pivot):
  // position() follows the arc instead of the chord. -1: none.
  int pivotFace = -1;
};

class MotionRule {
 public:
  virtual ~MotionRule() = default;
  virtual const char* name() const = 0;
  // Plans the motion of block `id`, settled (not moving) in `world`, through `face` (already checked
  // to be in [0, faceCount)). Returns VS_OK with `plan` filled in, or the vs_status that move()
  // reports to the block program (VS_ERR_OUT_OF_WORLD, VS_ERR_CELL_OCCUPIED, VS_ERR_NO_NEIGHBOR ...).
  virtual int plan(const World& world, BlockId id, int face, MotionPlan& plan) const = 0;
};

// Straight translation to the cell behind the face, if it is inside the grid, a lattice cell and
// free (Smart Blocks; what TargetSpec::canTranslate selects).
class TranslationRule final : public MotionRule {
 public:
  const char* name() const override { return "translation"; }
  int plan(const World& world, BlockId id, int face, MotionPlan& plan) const override {
    return translate(world, id, face, plan);
  }
  // The same without a virtual call, inlined into the kernel's path for canTranslate targets (the
  // motions of the Smart Blocks benchmark are on its hot path).
  static int translate(const World& world, BlockId id, int face, MotionPlan& plan) {
    const Cell to = world.lattice().neighborCell(world.block(id).cell, face);
    if (!world.inBounds(to) || !world.lattice().isValidCell(to)) return VS_ERR_OUT_OF_WORLD;
    if (!world.isFree(to)) return VS_ERR_CELL_OCCUPIED;
    plan.to = to;
    plan.sweptFromFaces = plan.sweptToFaces = 0;
    plan.pivotFace = -1;
    return VS_OK;
  }
};

class Simulation;

// Asked by the kernel before a legal motion starts (Simulation::setMotionCheck): VS_OK lets it go,
// any other vs_status refuses it with that code. The reality checker's StabilityGuard is one.
class MotionCheck {
 public:
  virtual ~MotionCheck() = default;
  virtual int check(const Simulation& sim, BlockId id, const Cell& to) = 0;
};

// Calls fn(cell) for each swept cell of a plan (the masks as MotionPlan keeps them); a cell next to
// both ends may come twice.
template <class Fn>
void forEachSweptCell(const Lattice& lattice, const Cell& from, const Cell& to, std::uint16_t fromFaces,
                      std::uint16_t toFaces, Fn&& fn) {
  for (; fromFaces; fromFaces &= std::uint16_t(fromFaces - 1)) fn(lattice.neighborCell(from, __builtin_ctz(fromFaces)));
  for (; toFaces; toFaces &= std::uint16_t(toFaces - 1)) fn(lattice.neighborCell(to, __builtin_ctz(toFaces)));
}

// The point a fraction `f` (0..1) of the way from `from` to `to`: along the chord, or along the arc
// around `pivot` when there is one (both ends are then at the same distance from it).
Vec3 motionPoint(const Vec3& from, const Vec3& to, const Vec3* pivot, double f);

}  // namespace simcore
