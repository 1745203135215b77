// The meshes blocks are drawn with, one per target shape, for a block of size 1 centred at the
// origin (the renderer scales them by the world's block size): Blinky Blocks' cube, Smart Blocks'
// flat tile, Catoms 2D's cylinder (axis along y: the catoms live in the x-z plane) and Catoms 3D's
// near-sphere. Triangles, each vertex with its normal.
#pragma once

#include <vector>

#include "session_info.hpp"

namespace ide {

struct MeshVertex {
  float position[3];
  float normal[3];
};

std::vector<MeshVertex> blockMesh(BlockShape shape);

}  // namespace ide
