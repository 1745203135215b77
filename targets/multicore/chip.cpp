#include "chip.hpp"

#include <cstdlib>

namespace multicore {

std::optional<Topology> parseTopology(std::string_view name) {
  if (name == "mesh") return Topology::Mesh;
  if (name == "ring") return Topology::Ring;
  if (name == "full") return Topology::Full;
  return std::nullopt;
}

const char* topologyName(Topology t) {
  switch (t) {
    case Topology::Mesh:
      return "mesh";
    case Topology::Ring:
      return "ring";
    case Topology::Full:
      return "full";
  }
  return "?";
}

unsigned meshWidth(unsigned cores) {
  unsigned w = 1;
  while (w * w < cores) ++w;
  return w;
}

unsigned hops(const ChipSpec& chip, unsigned from, unsigned to) {
  if (from == to) return 0;
  switch (chip.topology) {
    case Topology::Full:
      return 1;
    case Topology::Ring: {
      const unsigned d = from > to ? from - to : to - from;
      return d < chip.cores - d ? d : chip.cores - d;
    }
    case Topology::Mesh: {
      const unsigned w = meshWidth(chip.cores);
      const int dx = int(from % w) - int(to % w), dy = int(from / w) - int(to / w);
      return unsigned(std::abs(dx) + std::abs(dy));
    }
  }
  return 1;
}

}  // namespace multicore
