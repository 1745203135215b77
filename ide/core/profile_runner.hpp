// Profiling the program from the IDE (Run > Profile on threads): the program runs with
// `meld -j N --profile` semantics for each thread count, one after the other, on a thread of its
// own so that the window stays live; the window polls for the result and opens the profiles
// (their speedup table) in the profile view. No Qt here, so that it runs under ThreadSanitizer.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "meldvm/program.hpp"

namespace ide {

class ProfileRunner {
 public:
  struct Result {
    std::vector<std::string> files;  // one profile per thread count, in the order asked
    std::string error;               // empty when every run succeeded
  };

  ProfileRunner() = default;
  ~ProfileRunner();  // waits for a run in progress to end
  ProfileRunner(const ProfileRunner&) = delete;
  ProfileRunner& operator=(const ProfileRunner&) = delete;

  // Starts the runs of `program` (compiled as `meld` compiles it) at each of `threads`, writing
  // `folder`/NAME.jN.json; false (and nothing started) while a previous one is still running.
  bool start(std::shared_ptr<const meldvm::Program> program, std::vector<std::string> args,
             std::vector<unsigned> threads, const std::string& folder, const std::string& name);
  bool running() const { return running_.load(); }
  // The result once the runs are over (once: it is handed over).
  std::optional<Result> take();
  // 1 and every power of two up to the machine's cores (as bench/multicore/run-b4.sh).
  static std::vector<unsigned> defaultThreadCounts();

 private:
  void join();

  std::thread worker_;
  std::atomic<bool> running_{false};
  Result result_;  // written by the worker before running_ goes false
};

}  // namespace ide
