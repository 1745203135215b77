// SplitMix64 (Steele, Lea and Flood): a fast 64-bit mixing function and the stream built on it.
// The one random generator of the project: the kernel seeds its per-block streams with it, the VM
// draws randint & co. from it, meldc draws the weights of data templates and @cluster @random.
#pragma once

#include <cstdint>

namespace support {

inline constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ull;

// A well-mixed 64-bit value of x (one step of the stream from state x).
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += kGolden;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

struct SplitMix64 {
  std::uint64_t state = 0;
  constexpr std::uint64_t next() {
    const std::uint64_t out = splitmix64(state);
    state += kGolden;
    return out;
  }
  // Uniform enough for weights and shuffles (the modulo bias is below 2^-40 for n < 2^24).
  constexpr std::uint64_t below(std::uint64_t n) { return next() % n; }
};

}  // namespace support
