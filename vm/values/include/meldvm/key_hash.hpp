// The hash of an index key whose fields are ints, nodes, booleans or threads (their bits are their
// identity), and its fold into a 32-bit bucket hash. The fact store hashes such keys so
// (FactTable, SlotHash), and native code looks the same keys up itself with the same arithmetic
// (meldc's ITER_KEY lowering): a change here changes MELD_NATIVE_ABI_VERSION (native_abi.h).
//
// One multiplication a field, not three rounds of a mixer each: every ITER_KEY and every stored
// fact of an indexed or de-duplicated table hashes its key. Odd multipliers keep distinct keys
// apart; the product's high half, which foldKeyHash mixes into the bucket number, depends on all
// the bits.
#pragma once

#include <cstdint>

namespace meldvm::key_hash {

inline constexpr std::uint64_t kNodeOffset = 0x6d656c64;
inline constexpr std::uint64_t kNodeMultiplier = 0x9e3779b97f4a7c15ull;
inline constexpr std::uint64_t kFieldMultiplier = 0xbf58476d1ce4e5b9ull;
inline constexpr unsigned kFinalShift = 29;

constexpr std::uint64_t start(std::uint32_t node) {
  return (std::uint64_t(node) + kNodeOffset) * kNodeMultiplier;
}
constexpr std::uint64_t addField(std::uint64_t h, std::uint64_t bits) {
  return (h ^ bits) * kFieldMultiplier;
}
constexpr std::uint64_t finish(std::uint64_t h) { return h ^ (h >> kFinalShift); }
// The 32 bits a SlotHash keeps of a hash (its bucket is these bits & mask).
constexpr std::uint32_t fold(std::uint64_t h) { return std::uint32_t(h ^ (h >> 32)); }

}  // namespace meldvm::key_hash
