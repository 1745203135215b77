#include "simcore/world.hpp"

#include <stdexcept>

namespace simcore {

World::World(std::unique_ptr<Lattice> lattice, GridSize size)
    : lattice_(std::move(lattice)), size_(size), faceCount_(lattice_->faceCount()) {
  if (size.x <= 0 || size.y <= 0 || size.z <= 0) throw std::invalid_argument("grid size must be positive");
  const std::size_t cells = std::size_t(size.x) * std::size_t(size.y) * std::size_t(size.z);
  if (cells > (std::size_t(1) << 36)) throw std::invalid_argument("grid too large");
  grid_.assign(cells, kEmpty);
}

BlockId World::addBlock(const Cell& cell, std::uint32_t color) {
  if (!inBounds(cell) || !lattice_->isValidCell(cell) || grid_[cellIndex(cell)] != kEmpty) return kNoBlock;
  if (blocks_.size() >= kReservedBit - 1) return kNoBlock;
  const BlockId id = BlockId(blocks_.size());
  Block b;
  b.cell = cell;
  b.color = color;
  blocks_.push_back(b);
  alive_.push_back(1);
  grid_[cellIndex(cell)] = id;
  return id;
}

}  // namespace simcore
