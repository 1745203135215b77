#include "session_info.hpp"

#include <cstdlib>
#include <sstream>

namespace ide {

namespace {

// "a,b,c" into up to n floats; false unless exactly n numbers.
bool parseFloats(const std::string& text, float* out, int n) {
  std::istringstream in(text);
  std::string item;
  int i = 0;
  while (std::getline(in, item, ',')) {
    if (i == n) return false;
    char* end = nullptr;
    const float v = std::strtof(item.c_str(), &end);
    if (end == item.c_str()) return false;
    out[i++] = v;
  }
  return i == n;
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
