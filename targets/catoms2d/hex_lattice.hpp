// The hexagonal lattice of Catoms 2D, in VisibleSim's convention: cells are (x, 0, z) in the x–z
// plane (y is always 0), rows along x, and every odd row (z odd) shifted by half a cell towards +x.
// A cell's six neighbors therefore depend on the parity of its row:
//
//   face            even row (z even)   odd row (z odd)
//   0 right         (x+1, z)            (x+1, z)
//   1 top-right     (x,   z+1)          (x+1, z+1)
//   2 top-left      (x-1, z+1)          (x,   z+1)
//   3 left          (x-1, z)            (x-1, z)
//   4 bottom-left   (x-1, z-1)          (x,   z-1)
//   5 bottom-right  (x,   z-1)          (x+1, z-1)
//
// Faces go counter-clockwise (seen with x to the right and z up), 60 degrees apart, face f pointing
// at angle 60*f; the face opposite f is (f + 3) % 6 in both parities. Centres: x + 0.5 on odd rows,
// rows sqrt(3)/2 apart, so all six neighbors are one block diameter away.
#pragma once

#include <array>

#include "simcore/lattice.hpp"

namespace targets {

class HexLattice final : public simcore::Lattice {
 public:
  static constexpr int kFaces = 6;
  // The table above: offset of the neighbor behind `face` for a row of parity `odd`.
  static const simcore::Cell& offset(bool odd, int face) { return (odd ? kOdd : kEven)[std::size_t(face)]; }
  static bool oddRow(const simcore::Cell& c) { return (c.z & 1) != 0; }  // also right for z < 0

  const char* name() const override { return "hexagonal"; }
  int faceCount() const override { return kFaces; }
  simcore::Cell neighborCell(const simcore::Cell& c, int face) const override {
    const simcore::Cell& d = offset(oddRow(c), face);
    return simcore::Cell{c.x + d.x, c.y, c.z + d.z};
  }
  int oppositeFace(const simcore::Cell&, int face) const override { return (face + 3) % kFaces; }
  simcore::Vec3 cellCenter(const simcore::Cell& c) const override;
  simcore::Vec3 csgPoint(const simcore::Cell& c) const override;
  // Only the plane y = 0 belongs to the lattice.
  bool isValidCell(const simcore::Cell& c) const override { return c.y == 0; }
  bool isPlanar() const override { return true; }

 private:
  static const std::array<simcore::Cell, kFaces> kEven, kOdd;
};

}  // namespace targets
