#include "catoms2d/rotation_rule.hpp"

#include "simcore/blockcode.h"

namespace targets {

int HexRotationRule::plan(const simcore::World& world, simcore::BlockId id, int face,
                          simcore::MotionPlan& plan) const {
  const simcore::Lattice& lattice = world.lattice();
  const int n = lattice.faceCount();  // 6; faces numbered around the catom
  const simcore::Cell from = world.block(id).cell;
  const simcore::Cell to = lattice.neighborCell(from, face);
  if (!world.inBounds(to) || !lattice.isValidCell(to)) return VS_ERR_OUT_OF_WORLD;
  if (!world.isFree(to)) return VS_ERR_CELL_OCCUPIED;
  // Without any pivot the answer is "no neighbor"; a pivot whose swept cell is blocked says why.
  int refusal = VS_ERR_NO_NEIGHBOR;
  for (const int side : {-1, +1}) {  // pivot behind face-1 (clockwise roll), then face+1
    const int pivotFace = (face + side + n) % n, sweptFace = (face - side + n) % n;
    if (world.neighbor(id, pivotFace) == simcore::kNoBlock) continue;
    const simcore::Cell swept = lattice.neighborCell(from, sweptFace);
    if (!world.inBounds(swept) || !lattice.isValidCell(swept)) {
      refusal = VS_ERR_OUT_OF_WORLD;
      continue;
    }
    if (!world.isFree(swept)) {
      refusal = VS_ERR_CELL_OCCUPIED;
      continue;
    }
    plan.to = to;
    plan.sweptFromFaces = std::uint16_t(1u << sweptFace);
    plan.sweptToFaces = 0;
    plan.pivotFace = pivotFace;
    return VS_OK;
  }
  return refusal;
}

}  // namespace targets
