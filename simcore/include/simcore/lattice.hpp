// Lattices: how cells are addressed, which cell lies behind each face, and where a cell sits in
// space. Square (4 faces) and cubic (6 faces) lattices share one table-driven implementation;
// hexagonal and FCC lattices (Catoms) whose offsets depend on the cell's parity implement the same
// interface with their own tables.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace simcore {

struct Cell {
  std::int32_t x = 0, y = 0, z = 0;
  friend bool operator==(const Cell&, const Cell&) = default;
};

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

class Lattice {
 public:
  virtual ~Lattice() = default;
  virtual const char* name() const = 0;
  virtual int faceCount() const = 0;
  // The cell behind `face` of `cell` (not bounds-checked).
  virtual Cell neighborCell(const Cell& cell, int face) const = 0;
  // The face of the neighbor cell that faces back at `cell` through `face`.
  virtual int oppositeFace(const Cell& cell, int face) const = 0;
  // Centre of the cell in world units of one block size.
  virtual Vec3 cellCenter(const Cell& cell) const = 0;
  // Where VisibleSim's CSG solids sample the cell (its "unscaled world position"): the centre,
  // except where VisibleSim's lattice places cells otherwise (Catoms 2D and 3D).
  virtual Vec3 csgPoint(const Cell& cell) const { return cellCenter(cell); }
  // Whether a block may occupy this cell (always, except for lattices with parity rules).
  virtual bool isValidCell(const Cell&) const { return true; }
  // Whether the lattice is two-dimensional (z must be 0 for square; y for hexagonal x-z).
  virtual bool isPlanar() const = 0;
};

// Square (2D) or cubic (3D) lattice with a face table in the target's own numbering.
class RegularLattice final : public Lattice {
 public:
  RegularLattice(std::string name, std::vector<Cell> faceOffsets, bool planar);
  const char* name() const override { return name_.c_str(); }
  int faceCount() const override { return int(offsets_.size()); }
  Cell neighborCell(const Cell& c, int face) const override {
    const Cell& d = offsets_[std::size_t(face)];
    return Cell{c.x + d.x, c.y + d.y, c.z + d.z};
  }
  int oppositeFace(const Cell&, int face) const override { return opposite_[std::size_t(face)]; }
  Vec3 cellCenter(const Cell& c) const override { return Vec3{double(c.x), double(c.y), double(c.z)}; }
  bool isPlanar() const override { return planar_; }
  const Cell& offset(int face) const { return offsets_[std::size_t(face)]; }

 private:
  std::string name_;
  std::vector<Cell> offsets_;
  std::vector<int> opposite_;
  bool planar_;
};

}  // namespace simcore
