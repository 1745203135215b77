// The Catoms 2D motion: a catom rolls 60 degrees around one of its neighbors (the pivot), keeping
// contact with it, into the cell adjacent to both. The block ABI's move(face) names the destination:
// the cell behind `face`. The cells adjacent to both the catom and that destination are the ones
// behind faces face-1 and face+1 (mod 6); one of them must hold the pivot, and the other is the
// cell the catom sweeps: half-way along the arc its disk reaches 0.27 diameters into that cell, so
// it must be empty. This is our reading of the published Catoms 2D rule ("rotation around a
// neighbor when the faces it needs are free"): to roll away from the pivot on face p in one sense,
// the catom's next two faces in that sense (the destination and the swept cell) must be free.
//
//   pivot behind face-1  ->  clockwise around the pivot,         swept cell behind face+1
//   pivot behind face+1  ->  counter-clockwise around the pivot, swept cell behind face-1
//
// Both rolls cannot be legal at once (each one's pivot is the other one's swept cell), so the
// destination alone determines pivot and sense. move(face) succeeds when
//   1. the destination is inside the grid (else VS_ERR_OUT_OF_WORLD) and free (VS_ERR_CELL_OCCUPIED);
//   2. a settled neighbor sits behind face-1 or face+1 (none: VS_ERR_NO_NEIGHBOR);
//   3. that pivot's swept cell is inside the grid (VS_ERR_OUT_OF_WORLD: the grid's edge is a wall)
//      and free (VS_ERR_CELL_OCCUPIED).
// The swept cell stays reserved for the whole roll. The pivot is checked when the roll starts; the
// kernel does not pin it (a pivot that moves away meanwhile is the program's own mistake).
#pragma once

#include "simcore/motion_rule.hpp"

namespace targets {

class HexRotationRule final : public simcore::MotionRule {
 public:
  const char* name() const override { return "rotation-60"; }
  int plan(const simcore::World& world, simcore::BlockId id, int face,
           simcore::MotionPlan& plan) const override;
};

}  // namespace targets
