// The face-centred cubic lattice of Catoms 3D, in VisibleSim's convention: cells (x, y, z) are
// stacked square layers, every odd layer (z odd) shifted by half a cell in x and y so that its
// cells sit in the hollows between four cells of the layers below and above; layers are sqrt(2)/2
// apart, so all 12 neighbors are one diameter away. Each cell has 4 neighbors in its own layer, 4
// above and 4 below; the offsets of those above and below depend on the parity of z:
//
//   connector   direction (dx,dy,dz)   z even        z odd
//   0  side0    (+1,   0,    0)        (+1, 0, 0)    (+1, 0, 0)
//   1  side1    ( 0,  +1,    0)        ( 0,+1, 0)    ( 0,+1, 0)
//   2  top2     (+.5, +.5,  +h)        ( 0, 0,+1)    (+1,+1,+1)
//   3  top3     (-.5, +.5,  +h)        (-1, 0,+1)    ( 0,+1,+1)
//   4  top4     (-.5, -.5,  +h)        (-1,-1,+1)    ( 0, 0,+1)
//   5  top5     (+.5, -.5,  +h)        ( 0,-1,+1)    (+1, 0,+1)
//   6  side6    (-1,   0,    0)        (-1, 0, 0)    (-1, 0, 0)
//   7  side7    ( 0,  -1,    0)        ( 0,-1, 0)    ( 0,-1, 0)
//   8  bottom8  (-.5, -.5,  -h)        (-1,-1,-1)    ( 0, 0,-1)
//   9  bottom9  (+.5, -.5,  -h)        ( 0,-1,-1)    (+1, 0,-1)
//   10 bottom10 (+.5, +.5,  -h)        ( 0, 0,-1)    (+1,+1,-1)
//   11 bottom11 (-.5, +.5,  -h)        (-1, 0,-1)    ( 0,+1,-1)
//
// (h = sqrt(2)/2.) The direction of a connector does not depend on parity, and connector f faces
// connector (f + 6) % 12 of the neighbor: side0/side6, side1/side7, top2/bottom8 ... top5/bottom11.
// This is VisibleSim's FCCLattice table (connectors 0..11 as in the C3D.meld include file).
#pragma once

#include <array>

#include "simcore/lattice.hpp"

namespace targets {

class FccLattice final : public simcore::Lattice {
 public:
  static constexpr int kFaces = 12;
  // The table above: offset of the neighbor behind `face` for a layer of parity `odd`.
  static const simcore::Cell& offset(bool odd, int face) { return (odd ? kOdd : kEven)[std::size_t(face)]; }
  static bool oddLayer(const simcore::Cell& c) { return (c.z & 1) != 0; }  // also right for z < 0

  const char* name() const override { return "fcc"; }
  int faceCount() const override { return kFaces; }
  simcore::Cell neighborCell(const simcore::Cell& c, int face) const override {
    const simcore::Cell& d = offset(oddLayer(c), face);
    return simcore::Cell{c.x + d.x, c.y + d.y, c.z + d.z};
  }
  int oppositeFace(const simcore::Cell&, int face) const override { return (face + 6) % kFaces; }
  simcore::Vec3 cellCenter(const simcore::Cell& c) const override;
  simcore::Vec3 csgPoint(const simcore::Cell& c) const override;
  bool isPlanar() const override { return false; }

 private:
  static const std::array<simcore::Cell, kFaces> kEven, kOdd;
};

}  // namespace targets
