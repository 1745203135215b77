// The kernel thread of the IDE. It owns the run (a vsim::Session) and is the only thread that
// touches it; the GUI sends commands and reads snapshots (snapshot.hpp), so nothing is shared
// unsynchronised. It learns of what happens in the run through simcore's observer interface (the
// console) and builds snapshots between slices of events; it includes no Qt.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "options.hpp"
#include "session_info.hpp"
#include "snapshot.hpp"

namespace ide {

class KernelLoop;
struct Command;

class SimController {
 public:
  SimController();
  ~SimController();
  SimController(const SimController&) = delete;
  SimController& operator=(const SimController&) = delete;

  // Builds the run that `options` describe (world, block program, seed ...) and starts its kernel
  // thread, paused at time 0. On failure (bad world, compile error, bad .so) the previous run is
  // gone, error() says why and the compiler's messages are in diagnostics(); returns false.
  bool open(const vsim::Options& options);
  // The same options again: the run from the start.
  bool restart() { return open(options_); }
  bool isOpen() const { return loop_ != nullptr; }
  const vsim::Options& options() const { return options_; }
  const SessionInfo& info() const { return info_; }
  const std::string& error() const { return openError_; }
  int errorCode() const { return openErrorCode_; }  // vsim's exit code for error()
  const std::string& diagnostics() const { return diagnostics_; }

  // Commands (asynchronous; the kernel thread applies them in order).
  // speed = simulated seconds per wall second; 0 = as fast as possible.
  void run(double speed = 0);
  void runUntil(simcore::SimTime t, double speed = 0);
  void pause();
  void step();
  void select(simcore::BlockId block);
  // The selected block's history (facts gained and lost, messages) in its snapshots; kept across
  // restarts. Off: nothing is recorded.
  void setHistory(bool on);
  // Whether the next open() makes the VM record derivations (why a fact exists).
  void setRecordDerivations(bool on) { recordDerivations_ = on; }
  bool recordsDerivations() const { return recordDerivations_; }
  // Asks why `fact` (as the dump prints it, like "!dist(2)") exists on `block`; the answer comes in
  // a later snapshot's `why` with the returned request number.
  std::uint64_t why(simcore::BlockId block, const std::string& fact);
  // The same for a fact as a user types it ("dist(2)@10", "!dist(@10, 2)"): the answer names the
  // block (or says what is wrong with the text).
  std::uint64_t why(const std::string& spec) { return why(simcore::kNoBlock, spec); }
  void tap(simcore::BlockId block);
  // While paused (or at the end): the block leaves the world; its neighbours are told.
  void removeBlock(simcore::BlockId block);
  // While paused (or at the end): a new block (the next id) at a cell, or in the first free cell
  // next to a block; it starts now and its neighbours are told. The console says where or why not.
  void addBlock(const simcore::Cell& cell);
  void addBlockNextTo(simcore::BlockId block);
  // Writes the world as it is now (cells, colours; camera, light and the block program kept) as
  // a world file that loads again; the console says when it is done or why it failed.
  void saveWorld(const std::string& path);
  // The console's trace filter (vsim --trace syntax; "" = the programs' own trace lines only).
  // Throws simcore::TraceFilterError for a bad filter.
  void setTraceFilter(const std::string& filter);

  // The latest snapshot (never null once open() succeeded).
  std::shared_ptr<const WorldSnapshot> snapshot() const;
  // Waits until a snapshot satisfies `done` (checked on each new one), or the timeout; for tests
  // and the headless screenshot. Returns the snapshot that satisfied it, or null.
  std::shared_ptr<const WorldSnapshot> waitFor(const std::function<bool(const WorldSnapshot&)>& done,
                                               std::chrono::milliseconds timeout) const;
  // Runs (as fast as possible) to time t, or to the end, and waits there; the snapshot then (null
  // when nothing is open). For the window-less modes.
  std::shared_ptr<const WorldSnapshot> runToAndWait(simcore::SimTime t);
  // Console lines since the last call (a bounded number is kept; older ones are dropped).
  std::vector<std::string> takeConsoleLines();

 private:
  void close();
  void post(Command c);  // to the kernel thread, when a run is open

  vsim::Options options_;
  SessionInfo info_;
  std::string openError_, diagnostics_;
  int openErrorCode_ = 0;
  std::uint64_t sessionCount_ = 0, whyRequests_ = 0;
  bool history_ = false, recordDerivations_ = false;
  std::unique_ptr<KernelLoop> loop_;
};

}  // namespace ide
