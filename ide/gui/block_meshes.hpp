// The meshes blocks are drawn with, one per target shape, for a block of size 1 centred at the
// origin (the renderer scales them by the world's block size): Blinky Blocks' cube, Smart Blocks'
// flat tile, Catoms 2D's cylinder (axis along y: the catoms live in the x-z plane) and Catoms 3D's
// near-sphere. Indexed triangles (counter-clockwise seen from outside), each vertex with its
// normal: a software renderer shades each vertex of an instance once, so shared vertices count.
#pragma once

#include <cstdint>
#include <vector>

#include "session_info.hpp"

namespace ide {

struct MeshVertex {
  float position[3];
  float normal[3];
};

struct Mesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint16_t> indices;
};

Mesh blockMesh(BlockShape shape);

}  // namespace ide
