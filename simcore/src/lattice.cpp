#include "simcore/lattice.hpp"

#include <stdexcept>

namespace simcore {

RegularLattice::RegularLattice(std::string name, std::vector<Cell> faceOffsets, bool planar)
    : name_(std::move(name)), offsets_(std::move(faceOffsets)), planar_(planar) {
  opposite_.assign(offsets_.size(), -1);
  for (std::size_t i = 0; i < offsets_.size(); ++i)
    for (std::size_t j = 0; j < offsets_.size(); ++j)
      if (offsets_[i].x == -offsets_[j].x && offsets_[i].y == -offsets_[j].y &&
          offsets_[i].z == -offsets_[j].z)
        opposite_[i] = int(j);
  for (int o : opposite_)
    if (o < 0) throw std::logic_error("lattice " + name_ + ": every face needs an opposite face");
}

}  // namespace simcore
