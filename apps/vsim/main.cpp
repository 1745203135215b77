// vsim: the headless simulator. Loads a world, loads a block program, runs, reports.
// Every failure maps to one documented exit code (options.hpp); nothing is left to a crash.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "jit_compiler.hpp"
#include "meldvm/derivation_log.hpp"
#include "multicore_run.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "session.hpp"
#include "simcore/gltf_export.hpp"
#include "simcore/simulation.hpp"
#include "simcore/stability.hpp"
#include "simcore/stats.hpp"
#include "simcore/trace.hpp"
#include "simcore/xml_world.hpp"

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

// --mobiles-csv: a line per physics step and mobile. Numbers with fixed decimals, so that two runs
// compare line by line.
class MobilesCsv final : public simcore::SimulationObserver {
 public:
  explicit MobilesCsv(std::ostream& out) : out_(out) { out_ << "t,mobile,x,y,angle\n"; }
  bool wantsEvents() const override { return false; }
  bool wantsMessages() const override { return false; }
  void onPhysicsStep(const simcore::Simulation& sim) override {
    const simcore::Physics& p = *sim.physics();
    char line[128];
    for (std::size_t i = 0; i < p.mobileCount(); ++i) {
      const Eigen::Vector2d at = p.positionMm(i);
      std::snprintf(line, sizeof line, "%.6f,%zu,%.4f,%.4f,%.4f\n", double(sim.now()) / double(simcore::kSecond), i,
                    at.x(), at.y(), p.angleDeg(i));
      out_ << line;
    }
  }

 private:
  std::ostream& out_;
};

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

// --check-stability before the run: the world as loaded is checked; with no block program that is
// all (the exit code is returned), otherwise `guard` is installed to check every motion.
std::optional<int> startStabilityCheck(const Options& o, Session& session,
                                       std::optional<simcore::StabilityGuard>& guard) {
  simcore::Simulation& sim = session.simulation();
  if (!sim.target().gravity.applies)
    throw Failure{kExitUsage, "--check-stability: " + sim.target().name +
                                  " blocks lie on a surface, not under gravity: nothing to check"};
  const simcore::StabilityReport initial = simcore::checkStability(sim.world(), sim.target());
  if (!session.hasBlockProgram()) {
    simcore::printStability(std::cout, initial, sim.target());
    return initial.stable() ? kExitOk : kExitUnstable;
  }
  if (!initial.stable()) {
    std::cerr << "vsim: " << (o.refuseUnstable ? "error" : "warning") << ": the world as loaded: ";
    simcore::printStability(std::cerr, initial, sim.target());
    if (o.refuseUnstable)
      throw Failure{kExitUnstable, "--refuse-unstable: the world does not hold as loaded, so every motion would be refused"};
  }
  guard.emplace(o.quiet ? nullptr : &std::cerr, o.refuseUnstable);
  sim.setMotionCheck(&*guard);
  return std::nullopt;
}

// After the run: the final configuration's verdict and the motions checked. Whether it stands.
bool reportStability(std::ostream& report, const simcore::Simulation& sim, const simcore::StabilityGuard& guard,
                     bool refused) {
  const simcore::StabilityReport final = simcore::checkStability(sim.world(), sim.target());
  simcore::printStability(report, final, sim.target());
  report << "motions checked " << guard.checked() << ", " << guard.unstable()
         << (refused ? " refused as unstable\n" : " would not hold\n");
  return final.stable();
}

int runVsim(const Options& o, const NativeCompiler& jit) {
  // Outputs first (fail fast), then inputs, then the run.
  Output json(o.jsonFile), exported(o.exportFile), gltf(o.gltfFile), mobilesCsv(o.mobilesCsv);
  std::unique_ptr<std::ofstream> traceFile;
  std::ostream* traceOut = &std::cerr;
  if (o.trace && o.traceFile == "-")
    traceOut = &std::cout;
  else if (o.trace && !o.traceFile.empty()) {
    traceFile = std::make_unique<std::ofstream>(o.traceFile, std::ios::binary);
    if (!*traceFile) throw Failure{kExitRuntime, "cannot write trace file '" + o.traceFile + "'"};
    traceOut = traceFile.get();
  }

  SessionStreams streams;
  streams.programOutput = &std::cout;
  streams.diagnostics = &std::cerr;
  streams.warnings = !o.quiet;
  Session session(o, streams, &jit);
  simcore::Simulation& sim = session.simulation();
  std::optional<simcore::StabilityGuard> guard;
  if (o.checkStability)
    if (const std::optional<int> exitNow = startStabilityCheck(o, session, guard)) return *exitNow;
  // --why: the facts are checked before the run (a typo fails at once), derivations recorded.
  std::vector<meldvm::FactAt> why;
  meldvm::DerivationLog derivations;
  for (const std::string& spec : o.why) {
    try {
      why.push_back(meldvm::parseFactSpec(spec, *session.meldProgram()));
    } catch (const std::invalid_argument& e) {
      throw Failure{kExitUsage, std::string("--why: ") + e.what()};
    }
  }
  if (!why.empty()) session.meld()->recordDerivations(&derivations);

  std::optional<MobilesCsv> trajectories;
  if (mobilesCsv.wanted()) {
    if (!sim.physics())
      throw Failure{kExitUsage, "--mobiles-csv: " + o.world + " has no mobiles (<mobileList>)"};
    trajectories.emplace(mobilesCsv.stream());
    sim.addObserver(&*trajectories);
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
  info.code = session.codePath();
  info.codeName = session.codeName();
  info.until = o.until;
  try {
    info.end = runSimulation(sim, o, progress);
  } catch (const std::exception& e) {
    throw Failure{kExitRuntime,
                  std::string("simulation failed at ") + simcore::formatTime(sim.now()) + ": " + e.what()};
  }
  traceOut->flush();
  info.counters = session.counters();
  if (!session.programError().empty())
    throw Failure{kExitRuntime,
                  "Meld program failed at " + simcore::formatTime(sim.now()) + ": " + session.programError()};
  if (traceFile) {
    traceFile->close();
    if (!*traceFile) throw Failure{kExitRuntime, "error while writing trace file '" + o.traceFile + "'"};
  }

  // The text report goes to stdout unless stdout carries JSON or XML.
  const bool stdoutTaken = o.jsonFile == "-" || o.exportFile == "-" || o.mobilesCsv == "-";
  std::ostream& report = stdoutTaken ? std::cerr : std::cout;
  if (!o.quiet) printSummary(report, sim, info);
  if (o.stats) simcore::printStatistics(report, sim.statistics(), sim.fingerprint());
  const bool unstable = guard && !reportStability(report, sim, *guard, o.refuseUnstable);
  report.flush();
  if (session.meld() && o.dump) {
    session.meld()->dump(std::cout);
    std::cout.flush();
  }
  for (std::size_t i = 0; i < why.size(); ++i) {
    if (!meldvm::printWhy(std::cout, derivations, why[i]))
      throw Failure{kExitRuntime, "--why: the run did not derive " + o.why[i] +
                                      " (values as --dump prints them, then @BLOCK)"};
  }
  if (!why.empty() && o.stats)
    report << "derivations     " << derivations.size() << " recorded, " << derivations.bytesInUse()
           << " bytes\n";
  std::cout.flush();
  if (mobilesCsv.wanted()) mobilesCsv.close();
  if (json.wanted()) {
    writeJsonReport(json.stream(), sim, info);
    json.close();
  }
  if (exported.wanted()) {
    // The exported world names the code and the seed that ran (--code and --seed may have chosen).
    simcore::WorldDescription ran = session.world();
    ran.code = session.codePath();
    ran.seed = sim.seed();
    simcore::exportWorldXml(sim, ran, exported.stream());
    exported.close();
  }
  if (gltf.wanted()) {
    simcore::exportGltf(sim, gltf.stream());
    gltf.close();
  }
  if (info.end == RunEnd::Interrupted) return kExitInterrupted;
  return unstable ? kExitUnstable : kExitOk;
}

int reportFailure(const Failure& f) {
  // Messages that already say "file:line:col: error:" stay as they are, for editors to parse.
  if (f.message.find(": error: ") != std::string::npos)
    std::cerr << f.message << '\n';
  else
    std::cerr << "vsim: error: " << f.message << '\n';
  return f.code;
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
    const JitCompiler jit(options.progress && !options.quiet && ::isatty(2));
    if (options.isMulticore()) return runMulticore(options, &jit);
    return runVsim(options, jit);
  } catch (const SessionError& e) {
    return reportFailure(Failure{e.code, e.message});
  } catch (const Failure& f) {
    return reportFailure(f);
  } catch (const std::exception& e) {
    std::cerr << "vsim: error: " << e.what() << '\n';
    return kExitRuntime;
  }
}
