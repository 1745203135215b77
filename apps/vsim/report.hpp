// What vsim says about a finished run: the text summary and the same facts as JSON.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "simcore/simulation.hpp"

namespace vsim {

// How the run ended.
enum class RunEnd { QueueEmpty, UntilReached, Interrupted };

// Facts about a run that the Simulation does not know itself.
struct RunInfo {
  std::string world;     // the world file as given
  std::string code;      // the block code file
  std::string codeName;  // the block program's own name
  std::optional<simcore::SimTime> until;
  RunEnd end = RunEnd::QueueEmpty;
  // Counters of the block program (the Meld VM's facts, rules, messages), shown after the
  // fingerprint as "name  value" and in JSON as "name_with_underscores": value.
  std::vector<std::pair<std::string, std::uint64_t>> counters;
};

// Blocks are listed one by one up to this many; larger worlds get the histogram only.
inline constexpr std::size_t kMaxBlocksListed = 20;

struct ColorCount {
  std::uint32_t rgb = 0;
  std::uint64_t count = 0;
};
// Final colors of the alive blocks: most frequent first, ties by color value (deterministic).
std::vector<ColorCount> colorHistogram(const simcore::World& world);

void printSummary(std::ostream& out, const simcore::Simulation& sim, const RunInfo& info);
void writeJsonReport(std::ostream& out, const simcore::Simulation& sim, const RunInfo& info);

}  // namespace vsim
