// Per-block random streams: PCG32 (O'Neill) whose increment is derived from the block id, so every
// block draws from its own sequence determined by (seed, block id) alone — results do not depend on
// the order in which blocks are created or scheduled. Only the 8-byte state is stored per block.
#pragma once

#include <cstdint>

#include "support/splitmix.hpp"

namespace simcore {

using support::splitmix64;

class BlockRng {
 public:
  static std::uint64_t initialState(std::uint64_t seed, std::uint32_t stream) {
    std::uint64_t state = 0;
    const std::uint64_t inc = increment(stream);
    state = state * kMultiplier + inc;
    state += splitmix64(seed ^ splitmix64(stream));
    state = state * kMultiplier + inc;
    return state;
  }
  static std::uint32_t next(std::uint64_t& state, std::uint32_t stream) {
    const std::uint64_t old = state;
    state = old * kMultiplier + increment(stream);
    const std::uint32_t xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
    const std::uint32_t rot = std::uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Lemire's nearly-divisionless unbiased bounded draw.
  static std::uint32_t below(std::uint64_t& state, std::uint32_t stream, std::uint32_t bound) {
    std::uint64_t m = std::uint64_t(next(state, stream)) * bound;
    std::uint32_t low = std::uint32_t(m);
    if (low < bound) {
      const std::uint32_t threshold = (0u - bound) % bound;
      while (low < threshold) {
        m = std::uint64_t(next(state, stream)) * bound;
        low = std::uint32_t(m);
      }
    }
    return std::uint32_t(m >> 32);
  }

 private:
  static constexpr std::uint64_t kMultiplier = 6364136223846793005ull;
  static std::uint64_t increment(std::uint32_t stream) { return (std::uint64_t(stream) << 1) | 1u; }
};

}  // namespace simcore
