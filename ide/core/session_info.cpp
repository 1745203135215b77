#include "session_info.hpp"

namespace ide {

namespace {

// Exactly n numbers ("a,b,c"), as world files write them.
bool parseFloats(const std::string& text, float* out, std::size_t n) {
  const auto v = simcore::parseRealList(text);
  if (!v || v->size() != n) return false;
  for (std::size_t i = 0; i < n; ++i) out[i] = float((*v)[i]);
  return true;
}

}  // namespace

BlockShape shapeOfTarget(const std::string& targetName) {
  if (targetName == "smartblocks") return BlockShape::Tile;
  if (targetName == "catoms2d") return BlockShape::Cylinder;
  if (targetName == "catoms3d") return BlockShape::Sphere;
  return BlockShape::Cube;
}

std::optional<ViewPoint> parseViewPoint(const simcore::KeptElement& element) {
  if (!element.present) return std::nullopt;
  ViewPoint v;
  bool target = false, direction = false;
  for (const auto& [name, value] : element.attributes) {
    if (name == "target") target = parseFloats(value, v.target.data(), 3);
    if (name == "directionSpherical") {
      float d[3];
      direction = parseFloats(value, d, 3);
      if (direction) v.thetaDeg = d[0], v.phiDeg = d[1], v.distance = d[2];
    }
    if (name == "angle") parseFloats(value, &v.angleDeg, 1);
  }
  if (!target || !direction || v.distance <= 0) return std::nullopt;
  return v;
}

std::array<float, 3> blockSizeOf(const simcore::WorldDescription& world, double targetSizeMm) {
  std::array<float, 3> size{float(targetSizeMm), float(targetSizeMm), float(targetSizeMm)};
  float parsed[3];
  if (!world.blockSize.empty() && parseFloats(world.blockSize, parsed, 3) && parsed[0] > 0 && parsed[1] > 0 &&
      parsed[2] > 0)
    size = {parsed[0], parsed[1], parsed[2]};
  return size;
}

}  // namespace ide
