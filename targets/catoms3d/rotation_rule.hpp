// The Catoms 3D motion: a catom rotates over the surface of one of its neighbors (the pivot) from
// its cell A to a cell B next to both A and the pivot P, 60 degrees around P. The block ABI's
// move(face) names B, the cell behind `face` of A. The rules are those of the published Catoms 3D
// rotations as VisibleSim applies them seen from the pivot: the twelve cells around P form a
// cuboctahedron, whose edge A-B borders one triangle (A, B, K) and one square (A, B, C, D), and the
// catom rolls over P's face on one of them —
//
//   through the triangle ("hexagonal face" of P): K must be free;
//   through the square ("octagonal face" of P):   C (next to B) and D (next to A) must be free;
//   and in both: the cell beyond B away from P (2B - P) and the cell beyond A (2A - P) must be free
//   (a module there would be dragged along or struck).
//
// The pivot is any settled neighbor of A next to B (there are four such cells), tried in face order,
// each through the triangle first, then the square; the first legal rotation is taken. move() answers
//   VS_ERR_OUT_OF_WORLD   B is outside the grid;
//   VS_ERR_CELL_OCCUPIED  B is taken, or every pivot's rotations are blocked;
//   VS_ERR_NO_NEIGHBOR    no settled neighbor of A touches B (nothing to rotate on).
// Cells outside the grid do not block (nothing can be there, as in VisibleSim); the others stay
// reserved for the whole rotation. The centre follows the great circle around P's centre from A to
// B (VisibleSim draws two smaller turns through the face's centre; the end points are the same).
// A 90-degree rotation across the square's diagonal is two of these.
#pragma once

#include <array>
#include <cstdint>

#include "simcore/motion_rule.hpp"

namespace targets {

class FccRotationRule final : public simcore::MotionRule {
 public:
  FccRotationRule();
  const char* name() const override { return "fcc-rotation"; }
  int plan(const simcore::World& world, simcore::BlockId id, int face, simcore::MotionPlan& plan) const override;

  // One way to reach the cell behind a face: around the pivot behind `pivotFace` of A, through the
  // triangle or the square. The cells that must be free besides B, as faces of A and of B (a
  // connector's direction does not depend on the layer's parity, so neither do these).
  struct Rotation {
    int pivotFace;
    bool throughSquare;
    std::uint16_t fromFaces, toFaces;
  };
  static constexpr int kRotationsPerFace = 8;  // 4 pivots x (triangle, square)
  const std::array<Rotation, kRotationsPerFace>& rotations(int face) const { return table_[std::size_t(face)]; }

 private:
  std::array<std::array<Rotation, kRotationsPerFace>, 12> table_{};
};

}  // namespace targets
