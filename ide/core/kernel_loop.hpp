// The thread that runs one session: it applies the GUI's commands, runs the kernel in slices
// (paced to a speed, or as fast as possible) and publishes snapshots. Only this thread touches the
// session once it started.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "block_history.hpp"
#include "console_buffer.hpp"
#include "session.hpp"
#include "session_info.hpp"
#include "simcore/trace.hpp"
#include "snapshot.hpp"

namespace ide {

struct Command {
  enum Kind { Run, Pause, Step, Select, Tap, Trace, History, Why, Remove, Add, SaveWorld, Quit };
  explicit Command(Kind k) : kind(k) {}
  Kind kind;
  double speed = 0;                                 // Run: simulated s per wall s; 0 = as fast as possible
  simcore::SimTime until = simcore::kTimeInfinity;  // Run: stop (paused) at this time
  simcore::BlockId block = simcore::kNoBlock;       // Select, Tap
  simcore::TraceFilter filter;                      // Trace
  bool on = false;                                  // History
  simcore::Cell cell;                               // Add: the cell (block == kNoBlock), else next to block
  std::string fact;                                 // Why: the fact as the dump prints it; SaveWorld: path
  std::uint64_t request = 0;                        // Why
};

class KernelLoop {
 public:
  // Builds the session (on the caller's thread; throws vsim::SessionError, compiler messages to
  // `diagnostics`), then starts the thread, paused.
  // `recordDerivations`: the VM notes where every fact comes from, for Why commands.
  KernelLoop(const vsim::Options& options, std::uint64_t sessionId, std::ostream& diagnostics,
             bool recordDerivations);
  ~KernelLoop();  // stops and joins the thread

  const SessionInfo& info() const { return info_; }
  void post(Command c);
  std::shared_ptr<const WorldSnapshot> snapshot() const;
  std::shared_ptr<const WorldSnapshot> waitFor(const std::function<bool(const WorldSnapshot&)>& done,
                                               std::chrono::milliseconds timeout) const;
  std::vector<std::string> takeConsoleLines() { return console_.take(); }

 private:
  using Clock = std::chrono::steady_clock;
  void threadMain();
  bool apply(const Command& c);  // false: quit
  void runSlice();
  void finishIfOver();
  void publish();
  BlockDetails details(simcore::BlockId id);
  void followHistory();  // the history observer follows the selection (or goes)
  void answerWhy(const Command& c);
  void removeBlock(simcore::BlockId block);
  void addBlock(const Command& c);
  void saveWorld(const std::string& path);

  ConsoleBuffer console_;
  ConsoleStream consoleStream_{console_};
  std::unique_ptr<vsim::Session> session_;
  SessionInfo info_;
  std::optional<simcore::Trace> trace_;
  std::unique_ptr<BlockHistory> history_;
  bool historyWanted_ = false;
  std::unique_ptr<meldvm::DerivationLog> derivations_;
  std::shared_ptr<const WhyResult> why_;
  std::uint64_t sessionId_;

  // Kernel-thread state.
  RunState state_ = RunState::Paused;
  double speed_ = 0;
  simcore::SimTime until_ = simcore::kTimeInfinity;
  simcore::SimTime pacedFrom_ = 0;  // simulated time when the paced run (re)started
  Clock::time_point pacedSince_, lastPublish_;
  simcore::BlockId selected_ = simcore::kNoBlock;
  std::string error_;
  std::uint64_t serial_ = 0;

  // Shared with the GUI thread.
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;       // commands for the kernel thread
  mutable std::condition_variable published_;  // a new snapshot, for waitFor
  std::vector<Command> commands_;
  std::shared_ptr<const WorldSnapshot> latest_;
  // Set when the GUI reads a snapshot: while running, a new one is made only then (a GUI that
  // draws slowly costs the kernel fewer snapshots).
  mutable std::atomic<bool> snapshotWanted_{true};
  std::thread thread_;
};

}  // namespace ide
