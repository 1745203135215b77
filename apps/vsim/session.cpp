#include "session.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <ostream>

#include "code_search.hpp"
#include "meld_program.hpp"
#include "targets.hpp"

namespace vsim {

namespace {

simcore::TargetSpec chooseTarget(const Options& o, const simcore::WorldDescription& world,
                                 std::ostream* diagnostics) {
  std::string names;
  for (const std::string& n : targets::targetNames()) names += (names.empty() ? "" : ", ") + n;
  if (!o.target.empty()) {
    auto spec = targets::makeTarget(o.target);
    if (!spec) throw SessionError{kExitUsage, "unknown target '" + o.target + "' (targets: " + names + ")"};
    if (!world.target.empty() && diagnostics) {
      auto fromWorld = targets::makeTarget(world.target);
      if (!fromWorld || fromWorld->name != spec->name)
        *diagnostics << "vsim: warning: --target " << spec->name << " overrides target=\"" << world.target
                     << "\" of " << world.path << "\n";
    }
    return *spec;
  }
  if (world.target.empty()) return *targets::makeTarget("blinkyblocks");
  auto spec = targets::makeTarget(world.target);
  if (!spec)
    throw SessionError{
        kExitInput, simcore::XmlWorldError(world.path, world.targetPos.line, world.targetPos.column,
                                           "unknown target '" + world.target + "' (targets: " + names + ")")
                        .what()};
  return *spec;
}

void scheduleTaps(const Options& o, simcore::Simulation& sim) {
  for (const TapRequest& tap : o.taps) {
    if (!sim.target().hasTap)
      throw SessionError{kExitUsage, "--tap: " + sim.target().name + " blocks have no tap sensor"};
    if (tap.block >= sim.world().blockCount())
      throw SessionError{kExitUsage, "--tap: no block " + std::to_string(tap.block) + " (the world has " +
                                         std::to_string(sim.world().blockCount()) + " blocks, ids from 0)"};
    sim.scheduleTap(tap.block, tap.time);
  }
}

}  // namespace

simcore::WorldDescription loadWorldFile(const std::string& path) {
  // Checked here so that the message is the familiar "cannot open" naming the file.
  if (::access(path.c_str(), R_OK) != 0)
    throw SessionError{kExitInput, "cannot open world file '" + path + "': " + std::strerror(errno)};
  try {
    return simcore::loadWorldXml(path);
  } catch (const simcore::XmlWorldError& e) {
    throw SessionError{kExitInput, e.what()};
  }
}

Session::Session(const Options& o, const SessionStreams& streams, const NativeCompiler* jit)
    : world_(loadWorldFile(o.world)) {
  if (streams.warnings && streams.diagnostics)
    for (const std::string& w : world_.warnings) *streams.diagnostics << w << '\n';
  const simcore::TargetSpec target =
      chooseTarget(o, world_, streams.warnings ? streams.diagnostics : nullptr);
  loadBlockProgram(o, streams, jit);

  simcore::SimulationConfig config;
  config.seed = o.seed ? *o.seed : world_.seed.value_or(1);
  config.fes = o.fes;
  config.linkRateBitsPerSecond = o.linkRate;
  config.linkLatency = o.linkLatency;
  config.linkJitter = o.linkJitter;
  config.motionDuration = o.motionTime;
  if (o.physicsStep > 0) world_.airJets.step = o.physicsStep;
  sim_ = std::make_unique<simcore::Simulation>(target, world_.grid, config);
  try {
    simcore::populateSimulation(world_, *sim_);
  } catch (const simcore::XmlWorldError& e) {
    throw SessionError{kExitInput, e.what()};
  }
  scheduleTaps(o, *sim_);
  if (meldCode_)
    startMeld(o, streams);
  else if (library_)
    sim_->setBlockCode(library_->code());
}

Session::~Session() = default;

void Session::loadBlockProgram(const Options& o, const SessionStreams& streams, const NativeCompiler* jit) {
  // The command line wins; then the world's code= (a C BlockCode), then its program= (Meld).
  const std::string programPath = !o.program.empty()                      ? o.program
                                  : o.code.empty() && world_.code.empty() ? world_.program
                                                                          : std::string();
  codePath_ = !programPath.empty() ? programPath : !o.code.empty() ? o.code : world_.code;
  // `--check-stability` on a world without a program: the world is checked as it is.
  const bool checkAlone = o.checkStability && o.jsonFile.empty() && o.exportFile.empty() && o.gltfFile.empty() &&
                          !o.trace && !o.dump && o.why.empty() && !o.jit;
  if (codePath_.empty() && checkAlone) return;
  if (codePath_.empty())
    throw SessionError{kExitUsage,
                       "no block code: give --code LIB.so or --program PROG.meld (or code=\"LIB.so\" "
                       "or program=\"PROG.meld\" in " +
                           o.world + ")"};
  if (programPath.empty() &&
      (o.dump || o.timePerRule >= 0 || !o.includeDirs.empty() || !o.why.empty() || o.jit))
    throw SessionError{kExitUsage,
                       "--dump, --why, --time-per-rule, --jit and -I go with a Meld program (--program, "
                       "or program= in the world)"};
  if (o.jit && !jit) throw SessionError{kExitUsage, "--jit: native code cannot be compiled here (run vsim)"};
  if (!programPath.empty()) {
    try {
      meldCode_ = loadMeldCode(programPath, o.includeDirs, streams.diagnostics, true, o.jit ? jit : nullptr);
    } catch (const ProgramLoadError& e) {
      throw SessionError{kExitInput, e.what()};
    }
    return;
  }
  // A bare file name is searched for: next to the world (or here, for --code), on VSIM_CODE_PATH,
  // then in the installed and build folders next to this program (code_search.hpp).
  const std::string asWritten = !o.code.empty() ? o.code : world_.codeAsWritten;
  if (isBareName(asWritten)) {
    const std::string firstDir =
        !o.code.empty() ? std::string(".") : std::filesystem::path(o.world).parent_path().string();
    const std::vector<std::string> dirs = codeSearchPath(firstDir);
    if (const auto found = findBlockCode(asWritten, dirs)) {
      codePath_ = *found;
    } else {
      std::string looked;
      for (const std::string& d : dirs) looked += (looked.empty() ? "" : ", ") + d;
      throw SessionError{kExitInput, "block code '" + asWritten + "' not found; looked in " + looked +
                                         " (set VSIM_CODE_PATH to the folder that holds it)"};
    }
  }
  try {
    library_.emplace(simcore::BlockCodeLibrary::open(codePath_));
  } catch (const simcore::BlockCodeError& e) {
    throw SessionError{kExitInput, e.what()};
  }
}

void Session::startMeld(const Options& o, const SessionStreams& streams) {
  const simcore::TargetSpec& target = sim_->target();
  meldvm::BlockRuntimeOptions mo;
  mo.output = streams.programOutput;
  mo.native = meldCode_->native();
  mo.timePerRuleNs = o.timePerRule >= 0 ? o.timePerRule : target.programStepTime;
  mo.palette = o.paletteLm ? meldvm::Palette::LinearMeld : meldvm::Palette::VisibleSim;
  const simcore::World& w = sim_->world();
  const int faces = int(target.faceNames.size());
  for (simcore::BlockId b = 0; b < w.blockCount(); ++b)
    for (int f = 0; f < faces; ++f)
      (w.neighbor(b, f) != simcore::kNoBlock ? mo.neighborFacts : mo.vacantFacts)++;
  try {
    meld_ = std::make_unique<meldvm::BlockRuntime>(meldCode_->program(), std::uint32_t(w.blockCount()), mo);
  } catch (const meldvm::BlockProgramError& e) {
    throw SessionError{kExitInput, codePath_ + ": error: " + e.what()};
  }
  sim_->setBlockCode(meld_->blockcode());
}

std::string Session::codeName() const {
  return meld_ ? std::string("meld-vm") : library_ ? library_->name() : std::string();
}

std::string Session::programError() const { return meld_ ? meld_->error() : std::string(); }

std::vector<std::pair<std::string, std::uint64_t>> Session::counters() const {
  if (!meld_) return {};
  const meldvm::MachineStats& ms = meld_->machine().stats();
  return {{"facts derived", ms.factsDerived},
          {"facts consumed", ms.factsConsumed},
          {"rules fired", ms.rulesFired},
          {"fact messages", meld_->messages()},
          {"message bytes", meld_->messageBytes()},
          {"node runs", ms.nodeRuns},
          {"vm bytes", meld_->machine().bytesInUse()}};
}

}  // namespace vsim
