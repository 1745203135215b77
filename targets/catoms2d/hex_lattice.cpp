#include "catoms2d/hex_lattice.hpp"

#include <cmath>

namespace targets {

// The table of hex_lattice.hpp (y is always 0).
const std::array<simcore::Cell, HexLattice::kFaces> HexLattice::kEven = {
    {{1, 0, 0}, {0, 0, 1}, {-1, 0, 1}, {-1, 0, 0}, {-1, 0, -1}, {0, 0, -1}}};
const std::array<simcore::Cell, HexLattice::kFaces> HexLattice::kOdd = {
    {{1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {-1, 0, 0}, {0, 0, -1}, {1, 0, -1}}};

simcore::Vec3 HexLattice::cellCenter(const simcore::Cell& c) const {
  static const double kRowHeight = std::sqrt(3.0) / 2.0;
  return simcore::Vec3{double(c.x) + (oddRow(c) ? 0.5 : 0.0), double(c.y), double(c.z) * kRowHeight};
}

// VisibleSim's hexagonal lattice puts every cell at y = 2.5 for its CSG solids.
simcore::Vec3 HexLattice::csgPoint(const simcore::Cell& c) const {
  simcore::Vec3 p = cellCenter(c);
  p.y = 2.5;
  return p;
}

}  // namespace targets
