// meld: run a Meld program (source or bytecode) on its own graph and print its database (§8).
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <iostream>

#include "meldc/compile.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"
#include "meldvm/arith.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/derivation_log.hpp"
#include "meldvm/machine.hpp"
#include "options.hpp"

#ifndef MELD_VERSION
#define MELD_VERSION "unknown"
#endif

namespace {

bool endsWith(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

}  // namespace

int main(int argc, char** argv) {
  using namespace meldapp;
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

  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<meldvm::Program> program;
  if (endsWith(options->program, ".mbc")) {
    try {
      program = meldvm::readBytecodeFile(options->program);
    } catch (const meldvm::BytecodeError& e) {
      std::cerr << "meld: error: " << e.what() << "\n";  // the message names the file
      return kExitBadBytecode;
    }
  } else {
    meldc::SourceManager sources;
    meldc::Diagnostics diag(sources, std::cerr);
    try {
      program =
          meldc::compileProgram({options->program, options->includeDirs, options->defines}, sources, diag);
    } catch (const meldc::InternalCompilerError& e) {
      std::cerr << "meld: internal compiler error: " << e.what() << "\n";
      return 70;
    }
    if (!program) return kExitCompileErrors;
  }

  meldvm::MachineOptions mo;
  mo.args = options->programArgs;
  mo.output = &std::cout;
  mo.seed = options->seed;
  mo.maxSteps = options->maxSteps;
  const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto runStart = std::chrono::steady_clock::now();
  meldvm::Machine machine(*program, mo);
  // Facts asked about are checked before the run: a typo fails at once.
  std::vector<meldvm::FactAt> why;
  for (const std::string& spec : options->why) {
    try {
      why.push_back(meldvm::parseFactSpec(spec, *program));
    } catch (const std::invalid_argument& e) {
      std::cerr << "meld: error: --why: " << e.what() << "\n";
      return kExitUsage;
    }
  }
  meldvm::DerivationLog derivations;
  if (!why.empty()) machine.recordDerivations(&derivations);
  try {
    machine.run();
  } catch (const meldvm::RuntimeError& e) {
    std::cout.flush();
    std::cerr << "meld: " << e.what() << "\n";
    return kExitRuntimeError;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count();
  if (options->dump) machine.dump(std::cout);
  std::cout.flush();
  int status = kExitOk;
  for (std::size_t i = 0; i < why.size(); ++i) {
    if (!meldvm::printWhy(std::cout, derivations, why[i])) {
      std::cerr << "meld: no derivation of " << options->why[i]
                << ": the run did not derive it (the node first, "
                << "then the values as --dump prints them)\n";
      status = kExitNoSuchFact;
    }
  }
  std::cout.flush();
  if (options->stats) {
    const meldvm::MachineStats& s = machine.stats();
    std::fprintf(stderr,
                 "facts derived: %llu\nfacts consumed: %llu\nfacts sent: %llu\nrules fired: %llu\n"
                 "node runs: %llu\nload s: %.3f\nwall s: %.3f\nfacts/s: %.0f\npeak RSS MB: %.1f\n",
                 (unsigned long long)s.factsDerived, (unsigned long long)s.factsConsumed,
                 (unsigned long long)s.factsSent, (unsigned long long)s.rulesFired,
                 (unsigned long long)s.nodeRuns, loadSeconds, wall,
                 wall > 0 ? double(s.factsDerived) / wall : 0.0, peakRssMb());
    if (!why.empty())
      std::fprintf(stderr, "derivations recorded: %zu (%.1f MB)\n", derivations.size(),
                   double(derivations.bytesInUse()) / 1e6);
  }
  return status;
}
