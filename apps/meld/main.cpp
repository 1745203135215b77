// meld: run a Meld program (source or bytecode) on its own graph and print its database (§8).
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "loaded_program.hpp"
#include "meldvm/arith.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/derivation_log.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/threaded_machine.hpp"
#include "options.hpp"

#ifndef MELD_VERSION
#define MELD_VERSION "unknown"
#endif

namespace {

using namespace meldapp;
using Clock = std::chrono::steady_clock;

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void printStats(const meldvm::MachineStats& s, double loadSeconds, double wall, const meldvm::MemoryUse& vm,
                std::size_t nodes) {
  const std::size_t vmBytes = vm.total();
  std::fprintf(
      stderr,
      "facts derived: %llu\nfacts consumed: %llu\nfacts sent: %llu\nrules fired: %llu\n"
      "node runs: %llu\nfacts tried: %llu\nload s: %.3f\nwall s: %.3f\nfacts/s: %.0f\npeak RSS MB: %.1f\n",
      (unsigned long long)s.factsDerived, (unsigned long long)s.factsConsumed,
      (unsigned long long)s.factsSent, (unsigned long long)s.rulesFired, (unsigned long long)s.nodeRuns,
      (unsigned long long)s.factsTried, loadSeconds, wall, wall > 0 ? double(s.factsDerived) / wall : 0.0,
      peakRssMb());
  // The VM's own memory (stores, heaps, mailboxes, schedulers; all threads), per node of the graph.
  std::fprintf(stderr, "VM MB: %.1f\nVM bytes per node: %.0f\n", double(vmBytes) / 1e6,
               nodes ? double(vmBytes) / double(nodes) : 0.0);
  std::fprintf(
      stderr,
      "VM MB by part: fact tables %.1f, list heads %.1f, heaps %.1f, mailboxes %.1f, scheduling %.1f, "
      "buffers %.1f\n",
      double(vm.factTables) / 1e6, double(vm.listHeads) / 1e6, double(vm.heaps) / 1e6,
      double(vm.mailboxes) / 1e6, double(vm.scheduling) / 1e6, double(vm.buffers) / 1e6);
}

void printThreadTable(const std::vector<meldvm::ThreadStats>& threads) {
  std::fprintf(
      stderr,
      "threads: %zu\n%-6s %7s %10s %12s %13s %11s %11s %9s %7s %8s %8s %8s %10s %12s %12s %12s %8s %8s\n",
      threads.size(), "thread", "busy %", "node runs", "rules fired", "facts derived", "facts out",
      "facts in", "batches", "waits", "stolen", "given", "steal %", "rebalances", "bytes out", "facts tried",
      "bytes moved", "move ms", "mid-run");
  for (std::size_t t = 0; t < threads.size(); ++t) {
    const meldvm::ThreadStats& s = threads[t];
    const double total = s.busySeconds + s.idleSeconds;
    std::fprintf(
        stderr,
        "%-6zu %7.1f %10llu %12llu %13llu %11llu %11llu %9llu %7llu %8llu %8llu %8.1f %10llu %12llu "
        "%12llu %12llu "
        "%8.1f %8llu\n",
        t, total > 0 ? 100.0 * (s.busySeconds - s.rebalanceSeconds) / total : 0.0,
        (unsigned long long)s.nodeRuns, (unsigned long long)s.rulesFired, (unsigned long long)s.factsDerived,
        (unsigned long long)s.factsOut, (unsigned long long)s.factsIn, (unsigned long long)s.batchesOut,
        (unsigned long long)s.waits, (unsigned long long)s.nodesTaken, (unsigned long long)s.nodesGiven,
        total > 0 ? 100.0 * s.rebalanceSeconds / total : 0.0, (unsigned long long)s.rebalances,
        (unsigned long long)s.bytesOut, (unsigned long long)s.factsTried, (unsigned long long)s.bytesMoved,
        1e3 * s.rebalanceWorkSeconds, (unsigned long long)s.midRunRebalances);
  }
}

// Runs the machine (serial or threaded) and prints its dump if asked; false after a run-time
// error (reported).
template <class AnyMachine>
bool runAndDump(AnyMachine& machine, const Options& options, Clock::time_point runStart, double& wall) {
  try {
    machine.run();
  } catch (const meldvm::RuntimeError& e) {
    std::cout.flush();
    std::cerr << "meld: " << e.what() << "\n";
    return false;
  }
  wall = secondsSince(runStart);
  if (options.dump) machine.dump(std::cout);
  std::cout.flush();
  return true;
}

int runSerial(const Options& options, const meldvm::Program& program, meldvm::MachineOptions mo,
              double loadSeconds) {
  const Clock::time_point runStart = Clock::now();
  meldvm::Machine machine(program, mo);
  // Facts asked about are checked before the run: a typo fails at once.
  std::vector<meldvm::FactAt> why;
  for (const std::string& spec : options.why) {
    try {
      why.push_back(meldvm::parseFactSpec(spec, program));
    } catch (const std::invalid_argument& e) {
      std::cerr << "meld: error: --why: " << e.what() << "\n";
      return kExitUsage;
    }
  }
  meldvm::DerivationLog derivations;
  if (!why.empty()) machine.recordDerivations(&derivations);
  double wall = 0;
  if (!runAndDump(machine, options, runStart, wall)) return kExitRuntimeError;
  int status = kExitOk;
  for (std::size_t i = 0; i < why.size(); ++i) {
    if (!meldvm::printWhy(std::cout, derivations, why[i])) {
      std::cerr << "meld: no derivation of " << options.why[i]
                << ": the run did not derive it (the node first, "
                << "then the values as --dump prints them)\n";
      status = kExitNoSuchFact;
    }
  }
  std::cout.flush();
  if (options.stats) {
    printStats(machine.stats(), loadSeconds, wall, machine.memoryUse(), program.nodeSourceIds.size());
    if (!why.empty())
      std::fprintf(stderr, "derivations recorded: %zu (%.1f MB)\n", derivations.size(),
                   double(derivations.bytesInUse()) / 1e6);
  }
  return status;
}

int runThreaded(const Options& options, const meldvm::Program& program, meldvm::MachineOptions mo,
                double loadSeconds) {
  std::ofstream profile;
  if (!options.profile.empty()) {
    profile.open(options.profile);
    if (!profile) {
      std::cerr << "meld: error: --profile: cannot write " << options.profile << "\n";
      return kExitUsage;
    }
  }
  const Clock::time_point runStart = Clock::now();
  meldvm::ThreadedMachine machine(program, mo, options.threads);
  if (profile.is_open()) machine.recordProfile();
  double wall = 0;
  if (!runAndDump(machine, options, runStart, wall)) return kExitRuntimeError;
  if (options.stats) {
    printStats(machine.stats(), loadSeconds, wall, machine.memoryUse(), program.nodeSourceIds.size());
    printThreadTable(machine.threadStats());
  }
  if (profile.is_open()) {
    machine.writeProfile(profile);
    profile.close();
    if (!profile) {
      std::cerr << "meld: error: --profile: writing " << options.profile << " failed\n";
      return kExitRuntimeError;
    }
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  std::string error;
  const std::optional<Options> options = parseOptions({argv + 1, argv + argc}, error);
  if (!options) {
    std::cerr << "meld: error: " << error << "\n(run 'meld --help' for usage)\n";
    return kExitUsage;
  }
  if (options->help) {
    std::cout << usageText();
    return kExitOk;
  }
  if (options->version) {
    std::cout << "meld " << MELD_VERSION << " (bytecode version " << meldvm::kBytecodeVersion << ")\n";
    return kExitOk;
  }

  const Clock::time_point start = Clock::now();
  int status = kExitOk;
  const std::unique_ptr<LoadedProgram> loaded = loadProgram(*options, status);
  if (!loaded) return status;
  const meldvm::Program& program = *loaded->program;

  meldvm::MachineOptions mo;
  mo.native = loaded->native;
  mo.args = options->programArgs;
  mo.output = &std::cout;
  mo.seed = options->seed;
  mo.maxSteps = options->maxSteps;
  mo.coordination = !options->noScheduling;
  const double loadSeconds = secondsSince(start);
  return options->threads > 1 || !options->profile.empty() ? runThreaded(*options, program, mo, loadSeconds)
                                                           : runSerial(*options, program, mo, loadSeconds);
}
