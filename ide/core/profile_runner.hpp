// Profiling the program from the IDE (Run > Profile on threads): the program runs with
// `meld -j N --profile` semantics for each thread count, one after the other, on a thread of its
// own so that the window stays live; the window polls for the result and opens the profiles
// (their speedup table) in the profile view. No Qt here, so that it runs under ThreadSanitizer.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "meldvm/program.hpp"

namespace meldvm {
class ThreadedMachine;
}

namespace ide {

class ProfileRunner {
 public:
  struct Result {
    std::vector<std::string> files;  // one profile per thread count, in the order asked
    std::string error;               // empty when every run succeeded
    bool cancelled = false;          // cancel() stopped the runs: no error, no profile
  };

  ProfileRunner() = default;
  ~ProfileRunner();  // cancels a run in progress and waits for it to stop (closing the IDE)
  ProfileRunner(const ProfileRunner&) = delete;
  ProfileRunner& operator=(const ProfileRunner&) = delete;

  // Starts the runs of `program` (compiled as `meld` compiles it) at each of `threads`, writing
  // `folder`/NAME.jN.json; false (and nothing started) while a previous one is still running.
  bool start(std::shared_ptr<const meldvm::Program> program, std::vector<std::string> args,
             std::vector<unsigned> threads, const std::string& folder, const std::string& name);
  bool running() const { return running_.load(); }
  // Stops the runs: the one in progress stops after its current rule, the rest do not start;
  // the result is then `cancelled` and lists no profile. Returns at once.
  void cancel();
  // The result once the runs are over (once: it is handed over).
  std::optional<Result> take();
  // 1 and every power of two up to the machine's cores (as bench/multicore/run-b4.sh).
  static std::vector<unsigned> defaultThreadCounts();

 private:
  void join();
  // One run at `threads` threads, its profile written to `path`; false when cancelled (nothing
  // written); throws on an error.
  bool profileAt(const meldvm::Program& program, const std::vector<std::string>& args, unsigned threads,
                 const std::string& path);

  std::thread worker_;
  std::atomic<bool> running_{false};
  // cancel() and the worker meet here: the machine being run, if any, and whether to stop.
  std::mutex cancelLock_;
  meldvm::ThreadedMachine* current_ = nullptr;
  bool cancelled_ = false;
  Result result_;  // written by the worker before running_ goes false
};

}  // namespace ide
