#include "catoms3d/rotation_rule.hpp"

#include <cmath>
#include <stdexcept>

#include "catoms3d/fcc_lattice.hpp"
#include "simcore/blockcode.h"

namespace targets {

namespace {

using simcore::Vec3;
constexpr int kFaces = FccLattice::kFaces;

Vec3 minus(const Vec3& a, const Vec3& b) { return Vec3{a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 plus(const Vec3& a, const Vec3& b) { return Vec3{a.x + b.x, a.y + b.y, a.z + b.z}; }
double length(const Vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }

// The twelve connector directions (unit length: neighbors are one diameter apart).
std::array<Vec3, kFaces> connectorDirections() {
  const FccLattice lattice;
  const simcore::Cell origin{0, 0, 0};
  std::array<Vec3, kFaces> d{};
  for (int f = 0; f < kFaces; ++f)
    d[std::size_t(f)] = minus(lattice.cellCenter(lattice.neighborCell(origin, f)), lattice.cellCenter(origin));
  return d;
}

// The connector whose direction is v (a difference of two directions that is one itself).
int faceOf(const std::array<Vec3, kFaces>& dir, const Vec3& v) {
  for (int f = 0; f < kFaces; ++f)
    if (near(length(minus(dir[std::size_t(f)], v)), 0)) return f;
  throw std::logic_error("FccRotationRule: not a connector direction");
}

}  // namespace

// Works the rules of the header out on the directions, once: for a destination f and a pivot p (a
// neighbor of A one unit from B), K is the other neighbor of A one unit from both B and P; D is
// the neighbor of A one unit from P and sqrt(2) from B, and C = B + (D - A) is behind the same face
// of B; 2A - P is behind A's face opposite p, 2B - P behind B's face of direction B - P.
FccRotationRule::FccRotationRule() {
  const auto dir = connectorDirections();
  auto dist = [&](int a, int b) { return length(minus(dir[std::size_t(a)], dir[std::size_t(b)])); };
  for (int f = 0; f < kFaces; ++f) {
    int n = 0;
    for (int p = 0; p < kFaces; ++p) {
      if (p == f || !near(dist(p, f), 1)) continue;
      int k = -1, d = -1;
      for (int g = 0; g < kFaces; ++g) {
        if (g == f || g == p || !near(dist(g, p), 1)) continue;
        if (near(dist(g, f), 1)) k = g;
        else if (near(dist(g, f), std::sqrt(2.0)) &&
                 near(length(minus(plus(dir[std::size_t(f)], dir[std::size_t(g)]), dir[std::size_t(p)])), 1))
          d = g;
      }
      if (k < 0 || d < 0) throw std::logic_error("FccRotationRule: no triangle or square");
      const auto beyondA = std::uint16_t(1u << ((p + 6) % kFaces));
      const auto beyondB = std::uint16_t(1u << faceOf(dir, minus(dir[std::size_t(f)], dir[std::size_t(p)])));
      table_[std::size_t(f)][std::size_t(n++)] = Rotation{p, false, std::uint16_t(beyondA | 1u << k), beyondB};
      table_[std::size_t(f)][std::size_t(n++)] =
          Rotation{p, true, std::uint16_t(beyondA | 1u << d), std::uint16_t(beyondB | 1u << d)};
    }
    if (n != kRotationsPerFace) throw std::logic_error("FccRotationRule: not four pivots");
  }
}

int FccRotationRule::plan(const simcore::World& world, simcore::BlockId id, int face,
                          simcore::MotionPlan& plan) const {
  const simcore::Lattice& lattice = world.lattice();
  const simcore::Cell from = world.block(id).cell;
  const simcore::Cell to = lattice.neighborCell(from, face);
  if (!world.inBounds(to) || !lattice.isValidCell(to)) return VS_ERR_OUT_OF_WORLD;
  if (!world.isFree(to)) return VS_ERR_CELL_OCCUPIED;
  int refusal = VS_ERR_NO_NEIGHBOR;
  for (const Rotation& r : rotations(face)) {
    if (world.neighbor(id, r.pivotFace) == simcore::kNoBlock) continue;
    refusal = VS_ERR_CELL_OCCUPIED;
    // Only cells inside the grid are reserved; those outside are empty space.
    std::uint16_t fromFaces = 0, toFaces = 0;
    bool blocked = false;
    auto need = [&](const simcore::Cell& c, std::uint16_t bit, std::uint16_t& mask) {
      if (!world.inBounds(c)) return;
      if (!world.isFree(c)) blocked = true;
      mask = std::uint16_t(mask | bit);
    };
    for (int f = 0; f < kFaces; ++f) {
      const auto bit = std::uint16_t(1u << f);
      if (r.fromFaces & bit) need(lattice.neighborCell(from, f), bit, fromFaces);
      if (r.toFaces & bit) need(lattice.neighborCell(to, f), bit, toFaces);
    }
    if (blocked) continue;
    plan.to = to;
    plan.sweptFromFaces = fromFaces;
    plan.sweptToFaces = toFaces;
    plan.pivotFace = r.pivotFace;
    return VS_OK;
  }
  return refusal;
}

}  // namespace targets
