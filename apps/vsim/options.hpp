// vsim's command line: what the user asked for, parsed and checked before anything is loaded.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "multicore/chip.hpp"
#include "simcore/future_event_set.hpp"
#include "simcore/time.hpp"
#include "simcore/trace.hpp"

namespace vsim {

// Exit codes (documented in --help; scripts and tests rely on them).
enum ExitCode : int {
  kExitOk = 0,
  kExitRuntime = 1,       // the run failed, or an output file could not be written
  kExitUsage = 2,         // bad command line
  kExitInput = 3,         // bad world file, unknown target in it, block code that cannot be loaded
  kExitUnstable = 4,      // --check-stability: the final configuration does not hold
  kExitInterrupted = 130  // Ctrl-C: the run stopped early (the summary is still printed)
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TapRequest {
  std::uint32_t block = 0;
  simcore::SimTime time = 0;
};

// --target multicore: a Meld program on a simulated chip (multicore_run.hpp).
struct MulticoreOptions {
  std::vector<unsigned> cores;  // --cores N[,N...]; empty: 4
  multicore::ChipSpec chip;     // --topology, --hop-latency, --costs, --no-steal
  std::string profile;          // --profile FILE.json
};

struct Options {
  std::string world;                      // the XML world file
  std::string code;                       // --code: overrides the world's code= attribute
  std::string program;                    // --program: a Meld program instead of a C BlockCode
  bool dump = false;                      // --dump: the final facts of every block
  bool jit = false;                       // --jit: the Meld program as native code
  simcore::SimTime timePerRule = -1;      // --time-per-rule (negative: the VM's default)
  bool paletteLm = false;                 // --palette lm
  std::vector<std::string> includeDirs;   // -I for the Meld compiler
  std::vector<std::string> why;           // --why FACT@BLOCK: print its derivation tree after the run
  std::string target;                     // --target: overrides the world's target= attribute
  std::optional<simcore::SimTime> until;  // --until; none = until the event queue is empty
  std::optional<std::uint64_t> seed;      // --seed; none = the world's seed, else 1
  simcore::FesKind fes = simcore::kDefaultFes;
  // Link and motion overrides of the target's defaults (negative = keep the target's).
  double linkRate = -1;
  simcore::SimTime linkLatency = -1, linkJitter = -1, motionTime = -1;
  bool stats = false;
  std::string jsonFile;    // --json ("-" = stdout)
  std::string exportFile;  // --export ("-" = stdout)
  std::string gltfFile;    // --export-gltf
  std::string mobilesCsv;       // --mobiles-csv: the mobiles' trajectories, a line per physics step
  simcore::SimTime physicsStep = -1;  // --physics-step (negative: the model's 1 ms)
  bool checkStability = false;  // --check-stability (also set by --refuse-unstable)
  bool refuseUnstable = false;  // --refuse-unstable
  bool trace = false;
  simcore::TraceFilter traceFilter;
  simcore::TraceFormat traceFormat = simcore::TraceFormat::Text;
  std::string traceFile;  // --trace-file; "" = stderr, "-" = stdout
  std::vector<TapRequest> taps;
  bool quiet = false;
  bool progress = true;  // --no-progress turns the terminal progress line off
  bool help = false;
  bool version = false;
  std::vector<std::string> programArgs;  // after `--`: @arg1 ... (the multicore target)
  MulticoreOptions multicore;
  bool isMulticore() const;  // --target multicore
};

// Parses argv; throws UsageError with a one-line message. The IDE can start without a world.
Options parseOptions(int argc, char** argv, bool worldRequired = true);

// Option values (options.cpp): a number in [0, max] (or (0, max] when `positive`), `what` naming
// it in the message; and the items of a comma-separated list, each handed to `use`.
double parseNumber(std::string_view option, std::string_view text, bool positive, double max,
                   const char* what);
template <class Use>
void forEachListItem(std::string_view text, Use&& use) {
  for (;;) {
    const auto comma = text.find(',');
    use(text.substr(0, comma));
    if (comma == std::string_view::npos) return;
    text.remove_prefix(comma + 1);
  }
}

// The options of --target multicore (multicore_options.cpp): true if `arg` is one of them.
bool parseMulticoreOption(std::string_view arg, const std::function<std::string_view()>& value,
                          MulticoreOptions& m);
// Refuses world options with --target multicore and multicore options without it; fills defaults.
void checkMulticoreOptions(Options& o, bool multicoreOptionGiven);

// The --help text.
const char* usageText();

}  // namespace vsim
