// The configuration of a simulation as a glTF 2.0 binary file (.glb) for renderers (Blender opens
// it with its bundled importer): one node per block at its position, one material per colour.
#pragma once

#include <ostream>

#include "simcore/simulation.hpp"

namespace simcore {

// Writes the blocks as they are now (a moving block where its motion has brought it). Units are
// metres (the target's block size), +Y is up (glTF's convention; the world's +Z). Catoms are
// spheres, the other targets cubes, of the target's block size. Throws std::runtime_error when
// the stream fails.
void exportGltf(const Simulation& sim, std::ostream& out);

}  // namespace simcore
