// What stays fixed during one session (until the next restart): the target, the scale, the
// world's camera and light, the program that runs. Read by the GUI without locking.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "simcore/xml_world.hpp"

namespace ide {

enum class BlockShape : std::uint8_t { Cube, Tile, Cylinder, Sphere };

// directionSpherical="theta,phi,distance" about a target, with a field of view: VisibleSim's
// <camera> and <spotlight> (angles in degrees, lengths in mm).
struct ViewPoint {
  std::array<float, 3> target{0, 0, 0};
  float thetaDeg = 45, phiDeg = 30, distance = 500, angleDeg = 45;
};

struct SessionInfo {
  std::string worldPath, codePath, codeName, targetName;
  BlockShape shape = BlockShape::Cube;
  std::array<float, 3> blockSizeMm{40, 40, 40};
  simcore::GridSize grid;
  std::vector<std::string> faceNames;
  std::size_t blockCount = 0;
  bool meld = false;
  std::optional<ViewPoint> camera, spotlight;  // as the world file gives them
};

// The shape a target's blocks are drawn with.
BlockShape shapeOfTarget(const std::string& targetName);
// Reads <camera>/<spotlight> attributes; nullopt when absent or malformed.
std::optional<ViewPoint> parseViewPoint(const simcore::KeptElement& element);
// The world's blockSize="x,y,z" (mm), or the target's size in every direction.
std::array<float, 3> blockSizeOf(const simcore::WorldDescription& world, double targetSizeMm);

}  // namespace ide
