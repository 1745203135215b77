#include "catoms3d/fcc_lattice.hpp"

#include <cmath>

namespace targets {

// The table of fcc_lattice.hpp.
// clang-format off
const std::array<simcore::Cell, FccLattice::kFaces> FccLattice::kEven = {{
    {1, 0, 0}, {0, 1, 0},                                  // side0, side1
    {0, 0, 1}, {-1, 0, 1}, {-1, -1, 1}, {0, -1, 1},        // top2 .. top5
    {-1, 0, 0}, {0, -1, 0},                                // side6, side7
    {-1, -1, -1}, {0, -1, -1}, {0, 0, -1}, {-1, 0, -1}}};  // bottom8 .. bottom11
const std::array<simcore::Cell, FccLattice::kFaces> FccLattice::kOdd = {{
    {1, 0, 0}, {0, 1, 0},                                  // side0, side1
    {1, 1, 1}, {0, 1, 1}, {0, 0, 1}, {1, 0, 1},            // top2 .. top5
    {-1, 0, 0}, {0, -1, 0},                                // side6, side7
    {0, 0, -1}, {1, 0, -1}, {1, 1, -1}, {0, 1, -1}}};      // bottom8 .. bottom11
// clang-format on

simcore::Vec3 FccLattice::cellCenter(const simcore::Cell& c) const {
  static const double kLayerHeight = std::sqrt(2.0) / 2.0;
  const double shift = oddLayer(c) ? 0.5 : 0.0;
  return simcore::Vec3{double(c.x) + shift, double(c.y) + shift, double(c.z) * kLayerHeight};
}

// VisibleSim's FCC lattice, for its CSG solids: cells half a unit further in x and y, half a layer
// higher.
simcore::Vec3 FccLattice::csgPoint(const simcore::Cell& c) const {
  static const double kLayerHeight = std::sqrt(2.0) / 2.0;
  const simcore::Vec3 p = cellCenter(c);
  return simcore::Vec3{p.x + 0.5, p.y + 0.5, (double(c.z) + 0.5) * kLayerHeight};
}

}  // namespace targets
