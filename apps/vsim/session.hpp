// One simulated run as vsim's options describe it: the world file loaded, the target chosen, the
// block program loaded (a C BlockCode, or a Meld program behind the VM's block runtime) and the
// simulation built and populated. vsim and vsim-ide build their runs through this one class, so
// that the same command line gives the same run, and the same fingerprint, in both.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "meld_program.hpp"
#include "meldvm/block_runtime.hpp"
#include "meldvm/program.hpp"
#include "options.hpp"
#include "simcore/blockcode_library.hpp"
#include "simcore/simulation.hpp"
#include "simcore/xml_world.hpp"

namespace vsim {

// A failure while building or running a session; `code` is one of vsim's exit codes (options.hpp).
// Messages that start with "file:line:col: error:" are kept in that form for editors to parse.
struct SessionError {
  int code;
  std::string message;
};

struct SessionStreams {
  std::ostream* programOutput = nullptr;  // the Meld program's write-string (nullptr: discarded)
  std::ostream* diagnostics = nullptr;    // compiler messages and world warnings (nullptr: discarded)
  bool warnings = true;                   // report the world file's warnings to `diagnostics`
};

class Session {
 public:
  // Throws SessionError (kExitUsage, kExitInput) with a message naming the file. `jit` compiles a
  // Meld program to native code for --jit (without one, --jit is refused).
  Session(const Options& options, const SessionStreams& streams, const NativeCompiler* jit = nullptr);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  simcore::Simulation& simulation() { return *sim_; }
  const simcore::Simulation& simulation() const { return *sim_; }
  const simcore::WorldDescription& world() const { return world_; }
  // The Meld block runtime, when the block program is a Meld program.
  meldvm::BlockRuntime* meld() { return meld_.get(); }
  const meldvm::BlockRuntime* meld() const { return meld_.get(); }
  const meldvm::Program* meldProgram() const { return meldCode_ ? &meldCode_->program() : nullptr; }
  // The file that runs on the blocks (a .so, .meld or .mbc) and the block program's own name.
  const std::string& codePath() const { return codePath_; }
  std::string codeName() const;
  bool isMeld() const { return meld_ != nullptr; }
  // Whether a block program runs (not so for `--check-stability` on a world alone).
  bool hasBlockProgram() const { return meld_ != nullptr || library_.has_value(); }
  // The Meld program's first run-time error, or empty.
  std::string programError() const;
  // The block program's counters for reports (the Meld VM's facts, rules, messages).
  std::vector<std::pair<std::string, std::uint64_t>> counters() const;

 private:
  void loadBlockProgram(const Options& o, const SessionStreams& streams, const NativeCompiler* jit);
  void startMeld(const Options& o, const SessionStreams& streams);

  simcore::WorldDescription world_;
  std::string codePath_;
  // Declared before the simulation: the code table must outlive it.
  std::optional<simcore::BlockCodeLibrary> library_;
  std::unique_ptr<MeldCode> meldCode_;
  std::unique_ptr<simcore::Simulation> sim_;
  std::unique_ptr<meldvm::BlockRuntime> meld_;
};

// The world file as vsim reads it; throws SessionError (kExitInput) naming the file.
simcore::WorldDescription loadWorldFile(const std::string& path);

}  // namespace vsim
