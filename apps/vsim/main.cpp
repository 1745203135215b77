// vsim: the headless simulator. Loads a world, loads a block program, runs, reports.
// Every failure maps to one documented exit code (options.hpp); nothing is left to a crash.
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "meld_program.hpp"
#include "meldvm/block_runtime.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "simcore/blockcode_library.hpp"
#include "simcore/simulation.hpp"
#include "simcore/stats.hpp"
#include "simcore/trace.hpp"
#include "simcore/xml_world.hpp"
#include "targets.hpp"

#ifndef VSIM_VERSION
#define VSIM_VERSION "unknown"
#endif

namespace {

using namespace vsim;

// An error that ends the program with a given exit code; main prints it.
struct Failure {
  int code;
  std::string message;
};

volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) { gInterrupted = 1; }

// Output files are opened before the run, so that a typo in a path fails in a second, not after
// an hour of simulation.
class Output {
 public:
  explicit Output(const std::string& path) : path_(path) {
    if (path.empty() || path == "-") return;
    file_ = std::make_unique<std::ofstream>(path, std::ios::binary);
    if (!*file_) throw Failure{kExitRuntime, "cannot write '" + path + "'"};
  }
  bool wanted() const { return !path_.empty(); }
  std::ostream& stream() { return file_ ? *file_ : std::cout; }
  void close() {
    if (!file_) {
      std::cout.flush();
      return;
    }
    file_->close();
    if (!*file_) throw Failure{kExitRuntime, "error while writing '" + path_ + "'"};
  }

 private:
  std::string path_;
  std::unique_ptr<std::ofstream> file_;
};

simcore::TargetSpec chooseTarget(const Options& o, const simcore::WorldDescription& world) {
  std::string names;
  for (const std::string& n : targets::targetNames()) names += (names.empty() ? "" : ", ") + n;
  if (!o.target.empty()) {
    auto spec = targets::makeTarget(o.target);
    if (!spec) throw Failure{kExitUsage, "unknown target '" + o.target + "' (targets: " + names + ")"};
    if (!world.target.empty() && !o.quiet) {
      auto fromWorld = targets::makeTarget(world.target);
      if (!fromWorld || fromWorld->name != spec->name)
        std::cerr << "vsim: warning: --target " << spec->name << " overrides target=\"" << world.target
                  << "\" of " << world.path << "\n";
    }
    return *spec;
  }
  if (world.target.empty()) return *targets::makeTarget("blinkyblocks");
  auto spec = targets::makeTarget(world.target);
  if (!spec)
    throw Failure{kExitInput, simcore::XmlWorldError(world.path, world.targetPos.line, world.targetPos.column,
                                                     "unknown target '" + world.target + "' (targets: " + names + ")")
                                  .what()};
  return *spec;
}

simcore::WorldDescription loadWorld(const Options& o) {
  // Checked here so that the message is the familiar "cannot open" naming the file.
  if (::access(o.world.c_str(), R_OK) != 0)
    throw Failure{kExitInput, "cannot open world file '" + o.world + "': " + std::strerror(errno)};
  try {
    return simcore::loadWorldXml(o.world);
  } catch (const simcore::XmlWorldError& e) {
    throw Failure{kExitInput, e.what()};
  }
}

void scheduleTaps(const Options& o, simcore::Simulation& sim) {
  for (const TapRequest& tap : o.taps) {
    if (!sim.target().hasTap)
      throw Failure{kExitUsage, "--tap: " + sim.target().name + " blocks have no tap sensor"};
    if (tap.block >= sim.world().blockCount())
      throw Failure{kExitUsage, "--tap: no block " + std::to_string(tap.block) + " (the world has " +
                                    std::to_string(sim.world().blockCount()) + " blocks, ids from 0)"};
    sim.scheduleTap(tap.block, tap.time);
  }
}

// Runs in slices of events so that the progress line and Ctrl-C are looked at regularly.
RunEnd runSimulation(simcore::Simulation& sim, const Options& o, ProgressLine& progress) {
  constexpr std::uint64_t kSliceEvents = 1u << 16;
  const simcore::SimTime until = o.until.value_or(simcore::kTimeInfinity);
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  action.sa_flags = SA_RESETHAND;  // a second Ctrl-C kills at once
  struct sigaction previous {};
  sigaction(SIGINT, &action, &previous);
  RunEnd end = RunEnd::QueueEmpty;
  for (;;) {
    const simcore::RunStatus status = sim.run(until, kSliceEvents);
    if (status == simcore::RunStatus::TimeLimit) end = RunEnd::UntilReached;
    if (status != simcore::RunStatus::EventLimit) break;
    if (gInterrupted) {
      end = RunEnd::Interrupted;
      break;
    }
    progress.update(sim);
  }
  sigaction(SIGINT, &previous, nullptr);
  progress.finish();
  return end;
}

int runVsim(const Options& o) {
  // Outputs first (fail fast), then inputs, then the run.
  Output json(o.jsonFile), exported(o.exportFile);
  std::unique_ptr<std::ofstream> traceFile;
  std::ostream* traceOut = &std::cerr;
  if (o.trace && o.traceFile == "-")
    traceOut = &std::cout;
  else if (o.trace && !o.traceFile.empty()) {
    traceFile = std::make_unique<std::ofstream>(o.traceFile, std::ios::binary);
    if (!*traceFile) throw Failure{kExitRuntime, "cannot write trace file '" + o.traceFile + "'"};
    traceOut = traceFile.get();
  }

  const simcore::WorldDescription world = loadWorld(o);
  if (!o.quiet)
    for (const std::string& w : world.warnings) std::cerr << w << '\n';
  const simcore::TargetSpec target = chooseTarget(o, world);

  // The command line wins; then the world's code= (a C BlockCode), then its program= (Meld).
  const std::string programPath =
      !o.program.empty() ? o.program : o.code.empty() && world.code.empty() ? world.program : std::string();
  const std::string codePath = !programPath.empty() ? programPath : !o.code.empty() ? o.code : world.code;
  if (codePath.empty())
    throw Failure{kExitUsage, "no block code: give --code LIB.so or --program PROG.meld (or code=\"LIB.so\" or "
                              "program=\"PROG.meld\" in " + o.world + ")"};
  if (programPath.empty() && (o.dump || o.timePerRule >= 0 || !o.includeDirs.empty()))
    throw Failure{kExitUsage, "--dump, --time-per-rule and -I go with a Meld program (--program, or program= "
                              "in the world)"};
  // Declared before the simulation: the code table must outlive it.
  std::optional<simcore::BlockCodeLibrary> library;
  std::unique_ptr<meldvm::Program> meldProgram;
  if (!programPath.empty()) {
    try {
      meldProgram = loadMeldProgram(programPath, o.includeDirs);
    } catch (const ProgramLoadError& e) {
      throw Failure{kExitInput, e.what()};
    }
  } else {
    try {
      library.emplace(simcore::BlockCodeLibrary::open(codePath));
    } catch (const simcore::BlockCodeError& e) {
      throw Failure{kExitInput, e.what()};
    }
  }

  simcore::SimulationConfig config;
  config.seed = o.seed ? *o.seed : world.seed.value_or(1);
  config.fes = o.fes;
  config.linkRateBitsPerSecond = o.linkRate;
  config.linkLatency = o.linkLatency;
  config.linkJitter = o.linkJitter;
  config.motionDuration = o.motionTime;
  simcore::Simulation sim(target, world.grid, config);
  try {
    simcore::populateSimulation(world, sim);
  } catch (const simcore::XmlWorldError& e) {
    throw Failure{kExitInput, e.what()};
  }
  scheduleTaps(o, sim);
  std::unique_ptr<meldvm::BlockRuntime> meld;
  if (meldProgram) {
    meldvm::BlockRuntimeOptions mo;
    mo.output = &std::cout;
    mo.timePerRuleNs = o.timePerRule >= 0 ? o.timePerRule : target.programStepTime;
    mo.palette = o.paletteLm ? meldvm::Palette::LinearMeld : meldvm::Palette::VisibleSim;
    const simcore::World& w = sim.world();
    const int faces = int(target.faceNames.size());
    for (simcore::BlockId b = 0; b < w.blockCount(); ++b)
      for (int f = 0; f < faces; ++f)
        (w.neighbor(b, f) != simcore::kNoBlock ? mo.neighborFacts : mo.vacantFacts)++;
    try {
      meld =
          std::make_unique<meldvm::BlockRuntime>(*meldProgram, std::uint32_t(sim.world().blockCount()), mo);
    } catch (const meldvm::BlockProgramError& e) {
      throw Failure{kExitInput, programPath + ": error: " + e.what()};
    }
    sim.setBlockCode(meld->blockcode());
  } else {
    sim.setBlockCode(library->code());
  }

  std::optional<simcore::Trace> trace;
  if (o.trace) {
    trace.emplace(*traceOut, o.traceFilter, o.traceFormat);
    sim.addObserver(&*trace);
  }

  const bool traceOnStderr = o.trace && traceOut == &std::cerr;
  ProgressLine progress(o.progress && !o.quiet && !traceOnStderr && ::isatty(2), o.until);
  RunInfo info;
  info.world = o.world;
  info.code = codePath;
  info.codeName = meld ? std::string("meld-vm") : library->name();
  info.until = o.until;
  try {
    info.end = runSimulation(sim, o, progress);
  } catch (const std::exception& e) {
    throw Failure{kExitRuntime,
                  std::string("simulation failed at ") + simcore::formatTime(sim.now()) + ": " + e.what()};
  }
  traceOut->flush();
  if (meld) {
    const meldvm::MachineStats& ms = meld->machine().stats();
    info.counters = {{"facts derived", ms.factsDerived},
                     {"facts consumed", ms.factsConsumed},
                     {"rules fired", ms.rulesFired},
                     {"fact messages", meld->messages()},
                     {"message bytes", meld->messageBytes()},
                     {"node runs", ms.nodeRuns},
                     {"vm bytes", meld->machine().bytesInUse()}};
  }
  if (meld && !meld->error().empty())
    throw Failure{kExitRuntime,
                  "Meld program failed at " + simcore::formatTime(sim.now()) + ": " + meld->error()};
  if (traceFile) {
    traceFile->close();
    if (!*traceFile) throw Failure{kExitRuntime, "error while writing trace file '" + o.traceFile + "'"};
  }

  // The text report goes to stdout unless stdout carries JSON or XML.
  const bool stdoutTaken = o.jsonFile == "-" || o.exportFile == "-";
  std::ostream& report = stdoutTaken ? std::cerr : std::cout;
  if (!o.quiet) printSummary(report, sim, info);
  if (o.stats) simcore::printStatistics(report, sim.statistics(), sim.fingerprint());
  report.flush();
  if (meld && o.dump) {
    meld->dump(std::cout);
    std::cout.flush();
  }
  if (json.wanted()) {
    writeJsonReport(json.stream(), sim, info);
    json.close();
  }
  if (exported.wanted()) {
    // The exported world names the code and the seed that ran (--code and --seed may have chosen).
    simcore::WorldDescription ran = world;
    ran.code = codePath;
    ran.seed = sim.seed();
    simcore::exportWorldXml(sim, ran, exported.stream());
    exported.close();
  }
  return info.end == RunEnd::Interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    options = parseOptions(argc, argv);
  } catch (const std::exception& e) {  // UsageError, TraceFilterError
    std::cerr << "vsim: error: " << e.what() << '\n';
    return kExitUsage;
  }
  if (options.help) {
    std::cout << usageText();
    return kExitOk;
  }
  if (options.version) {
    std::cout << "vsim " VSIM_VERSION " (block ABI " << VS_ABI_VERSION << ")\n";
    return kExitOk;
  }
  try {
    return runVsim(options);
  } catch (const Failure& f) {
    // Messages that already say "file:line:col: error:" stay as they are, for editors to parse.
    if (f.message.find(": error: ") != std::string::npos)
      std::cerr << f.message << '\n';
    else
      std::cerr << "vsim: error: " << f.message << '\n';
    return f.code;
  } catch (const std::exception& e) {
    std::cerr << "vsim: error: " << e.what() << '\n';
    return kExitRuntime;
  }
}
