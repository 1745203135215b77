// The world: a bounded grid of cells on a lattice, the blocks (stored contiguously, addressed by
// dense ids) and the cell -> block index that makes every neighbor lookup O(1).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simcore/lattice.hpp"
#include "support/large_allocator.hpp"

namespace simcore {

using BlockId = std::uint32_t;
inline constexpr BlockId kNoBlock = 0xFFFFFFFFu;

struct GridSize {
  std::int32_t x = 1, y = 1, z = 1;
};

// Kept to 32 bytes: a million of them are touched in random order every simulated second.
struct Block {
  std::uint64_t rng = 0;            // PCG32 state (stream = block id)
  Cell cell;                        // destination cell while moving
  std::uint32_t color = 0;          // 0xRRGGBB
  std::uint32_t motion = kNoBlock;  // motion slot while moving
};
static_assert(sizeof(Block) == 32);

using BlockVector = std::vector<Block, support::LargeAllocator<Block>>;

class World {
 public:
  World(std::unique_ptr<Lattice> lattice, GridSize size);

  const Lattice& lattice() const { return *lattice_; }
  GridSize size() const { return size_; }
  int faceCount() const { return faceCount_; }

  bool inBounds(const Cell& c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < size_.x && c.y < size_.y && c.z < size_.z;
  }
  std::size_t cellIndex(const Cell& c) const {
    return std::size_t(c.x) +
           std::size_t(size_.x) * (std::size_t(c.y) + std::size_t(size_.y) * std::size_t(c.z));
  }

  // Adds a block; returns its id, or kNoBlock if the cell is outside, invalid or taken.
  BlockId addBlock(const Cell& cell, std::uint32_t color);
  void reserveBlocks(std::size_t n) {
    blocks_.reserve(n);
    alive_.reserve(n);
  }
  // One byte per block, so that checking a block (notifications to neighbors) stays in cache.
  bool isAlive(BlockId id) const { return alive_[id] != 0; }
  std::size_t aliveCount() const {
    return std::size_t(std::count(alive_.begin(), alive_.end(), std::uint8_t(1)));
  }
  [[gnu::always_inline]] void prefetchAlive(BlockId id) const { __builtin_prefetch(&alive_[id]); }
  void markRemoved(BlockId id) { alive_[id] = 0; }
  std::size_t blockCount() const { return blocks_.size(); }
  Block& block(BlockId id) { return blocks_[id]; }
  const Block& block(BlockId id) const { return blocks_[id]; }
  const BlockVector& blocks() const { return blocks_; }

  // The block settled in a cell (not one moving into or out of it), or kNoBlock.
  BlockId settledAt(const Cell& c) const {
    if (!inBounds(c)) return kNoBlock;
    const std::uint32_t v = grid_[cellIndex(c)];
    return (v & kReservedBit) ? kNoBlock : v;
  }
  // Whether nothing occupies or has reserved the cell.
  bool isFree(const Cell& c) const { return inBounds(c) && grid_[cellIndex(c)] == kEmpty; }
  // Any block occupying or moving through the cell, or kNoBlock.
  BlockId anyAt(const Cell& c) const {
    if (!inBounds(c)) return kNoBlock;
    const std::uint32_t v = grid_[cellIndex(c)];
    return v == kEmpty ? kNoBlock : (v & ~kReservedBit);
  }

  // The neighbor linked to `face` of a settled block (kNoBlock if none, or if the block moves).
  BlockId neighbor(BlockId id, int face) const {
    const Block& b = blocks_[id];
    if (b.motion != kNoBlock || !alive_[id]) return kNoBlock;
    return settledAt(lattice_->neighborCell(b.cell, face));
  }

  // Hint: start loading the grid lines around a cell (the previous, same and next row and layer).
  // Always inlined: GCC deletes calls to functions whose only effect is a prefetch (it deems them pure).
  [[gnu::always_inline]] void prefetchAround(const Cell& c) const {
    if (!inBounds(c)) return;
    const std::size_t i = cellIndex(c), n = grid_.size();
    const std::size_t row = std::size_t(size_.x), layer = row * std::size_t(size_.y);
    const std::uint32_t* g = grid_.data();
    __builtin_prefetch(g + i);
    if (i >= row) __builtin_prefetch(g + i - row);
    if (i + row < n) __builtin_prefetch(g + i + row);
    if (size_.z > 1) {
      if (i >= layer) __builtin_prefetch(g + i - layer);
      if (i + layer < n) __builtin_prefetch(g + i + layer);
    }
  }

  // Grid bookkeeping for motions and removals (the kernel keeps links and events consistent).
  void reserve(const Cell& c, BlockId id) { grid_[cellIndex(c)] = id | kReservedBit; }
  void settle(const Cell& c, BlockId id) { grid_[cellIndex(c)] = id; }
  void clearCell(const Cell& c) { grid_[cellIndex(c)] = kEmpty; }

 private:
  static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
  static constexpr std::uint32_t kReservedBit = 0x80000000u;

  std::unique_ptr<Lattice> lattice_;
  GridSize size_;
  int faceCount_;
  std::vector<std::uint32_t, support::LargeAllocator<std::uint32_t>> grid_;
  BlockVector blocks_;
  std::vector<std::uint8_t> alive_;
};

}  // namespace simcore
