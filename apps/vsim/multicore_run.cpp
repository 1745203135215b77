#include "multicore_run.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "meld_chip.hpp"
#include "meld_program.hpp"

namespace vsim {

namespace {

struct ChipRun {
  unsigned cores = 0;
  simcore::SimTime time = 0;
  std::uint64_t rebalances = 0, factsAcross = 0;
  std::vector<multicore::CoreStats> perCore;
  meldvm::MachineStats totals;
  double hostSeconds = 0;
};

class RunFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One simulated run. The last run of a command is the one the user sees: its write-string
// output, its dump, its profile; the others (the one-core baseline, the other counts) are silent.
ChipRun simulate(const MeldCode& code, const Options& o, unsigned cores, bool shown, std::ostream* profile) {
  const meldvm::Program& program = code.program();
  meldvm::MachineOptions mo;
  mo.native = code.native();
  mo.args = o.programArgs;
  mo.output = shown ? &std::cout : nullptr;
  mo.seed = o.seed.value_or(0);
  const auto start = std::chrono::steady_clock::now();
  MeldChip chip(program, mo, cores);
  multicore::ChipSpec spec = o.multicore.chip;
  spec.cores = cores;
  spec.stealing = spec.stealing && chip.stealable();
  multicore::ChipSimulator sim(spec, chip, profile != nullptr);
  try {
    sim.run();
  } catch (const meldvm::RuntimeError& e) {
    std::cout.flush();
    throw RunFailure(std::string("Meld program failed on the ") + std::to_string(cores) +
                     "-core chip: " + e.what());
  }
  chip.finish();
  ChipRun r;
  r.cores = cores;
  r.time = sim.endTime();
  r.rebalances = sim.rebalances();
  r.perCore = sim.cores();
  for (const auto& c : r.perCore) r.factsAcross += c.factsOut;
  r.totals = chip.stats();
  r.hostSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (shown && o.dump) std::cout << chip.dump();
  if (profile) sim.writeProfile(*profile);
  return r;
}

void printSweep(std::ostream& out, const std::vector<ChipRun>& runs, const ChipRun& base) {
  out << "  cores    predicted ms  speedup  efficiency  rebalances  facts across cores  host s\n";
  for (const ChipRun& r : runs) {
    const double speedup = r.time > 0 ? double(base.time) / double(r.time) : 1.0;
    char line[160];
    std::snprintf(line, sizeof line, "  %5u  %14.6f  %7.2f  %10.2f  %10llu  %18llu  %6.2f\n", r.cores,
                  double(r.time) / 1e6, speedup, speedup / r.cores, (unsigned long long)r.rebalances,
                  (unsigned long long)r.factsAcross, r.hostSeconds);
    out << line;
  }
}

void printCores(std::ostream& out, const ChipRun& r) {
  out << "per core (" << r.cores << " cores):\n"
      << "  core  busy %  idle %  steal %  node runs  rules fired  facts derived  facts out  facts in"
         "  taken  given\n";
  for (std::size_t c = 0; c < r.perCore.size(); ++c) {
    const multicore::CoreStats& s = r.perCore[c];
    const double t = r.time > 0 ? double(r.time) : 1.0;
    char line[200];
    std::snprintf(line, sizeof line,
                  "  %4zu  %6.1f  %6.1f  %7.1f  %9llu  %11llu  %13llu  %9llu  %8llu  %5llu  %5llu\n", c,
                  100.0 * double(s.busyNs) / t, 100.0 * double(s.idleNs) / t, 100.0 * double(s.stealNs) / t,
                  (unsigned long long)s.nodeRuns, (unsigned long long)s.rules, (unsigned long long)s.facts,
                  (unsigned long long)s.factsOut, (unsigned long long)s.factsIn,
                  (unsigned long long)s.nodesTaken, (unsigned long long)s.nodesGiven);
    out << line;
  }
}

void printHeader(std::ostream& out, const Options& o, const meldvm::Program& program) {
  const multicore::ChipSpec& chip = o.multicore.chip;
  char line[200];
  std::snprintf(line, sizeof line,
                "multicore: %s, %.0f ns per hop, stealing %s; costs (ns; contention: a factor):",
                multicore::topologyName(chip.topology), chip.hopLatency, chip.stealing ? "on" : "off");
  out << line;
  const char* sep = " ";
  for (const multicore::CostName& c : multicore::kCostNames) {
    std::snprintf(line, sizeof line, "%s%s %.10g", sep, c.name, chip.costs.*c.cost);
    out << line;
    sep = ", ";
  }
  out << "\nprogram: " << o.program << ", " << program.nodeSourceIds.size() << " nodes\n";
}

}  // namespace

int runMulticore(const Options& o, const NativeCompiler* jit) {
  std::ofstream profile;
  if (!o.multicore.profile.empty()) {
    profile.open(o.multicore.profile, std::ios::binary);
    if (!profile) {
      std::cerr << "vsim: error: --profile: cannot write '" << o.multicore.profile << "'\n";
      return kExitRuntime;
    }
  }
  if (o.jit && !jit) {
    std::cerr << "vsim: error: --jit: native code cannot be compiled here\n";
    return kExitUsage;
  }
  std::unique_ptr<MeldCode> code;
  try {
    code = loadMeldCode(o.program, o.includeDirs, &std::cerr, /*robots=*/false, o.jit ? jit : nullptr);
  } catch (const ProgramLoadError& e) {
    std::cerr << "vsim: error: " << e.what() << '\n';
    return kExitInput;
  }
  const std::vector<unsigned>& counts = o.multicore.cores;
  std::vector<ChipRun> runs;
  try {
    std::optional<ChipRun> base;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      const bool last = i + 1 == counts.size();
      runs.push_back(simulate(*code, o, counts[i], last, last && profile.is_open() ? &profile : nullptr));
      if (counts[i] == 1 && !base) base = runs.back();
    }
    if (!base) base = simulate(*code, o, 1, false, nullptr);  // the speedups' reference
    std::cout.flush();
    if (!o.quiet) {
      printHeader(std::cout, o, code->program());
      printSweep(std::cout, runs, *base);
      printCores(std::cout, runs.back());
      const meldvm::MachineStats& t = runs.back().totals;
      std::printf("facts derived %llu, rules fired %llu, node runs %llu (%u cores)\n",
                  (unsigned long long)t.factsDerived, (unsigned long long)t.rulesFired,
                  (unsigned long long)t.nodeRuns, runs.back().cores);
    }
  } catch (const RunFailure& e) {
    std::cerr << "vsim: error: " << e.what() << '\n';
    return kExitRuntime;
  } catch (const std::exception& e) {  // bad_alloc, invalid_argument
    std::cerr << "vsim: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  std::cout.flush();
  if (profile.is_open()) {
    profile.close();
    if (!profile) {
      std::cerr << "vsim: error: --profile: writing '" << o.multicore.profile << "' failed\n";
      return kExitRuntime;
    }
  }
  return kExitOk;
}

}  // namespace vsim
