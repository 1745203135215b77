// Where instructions came from, for the derivation trees (why a fact exists) and messages; no
// effect on runs.
#pragma once

#include <cstdint>
#include <span>

namespace meldvm {

// From `pc` on (until the next entry), Program::sourceFiles[file], 1-based `line`.
struct SourceLine {
  std::uint32_t pc = 0, file = 0, line = 0;
  friend bool operator==(const SourceLine&, const SourceLine&) = default;
};

// The entry in force at `pc` of a block's lines (by increasing pc), or nullptr.
inline const SourceLine* lineAt(std::span<const SourceLine> lines, std::uint32_t pc) {
  const SourceLine* found = nullptr;
  for (const SourceLine& l : lines) {
    if (l.pc > pc) break;
    found = &l;
  }
  return found;
}

}  // namespace meldvm
