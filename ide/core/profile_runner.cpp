#include "profile_runner.hpp"

#include <fstream>

#include "meldvm/threaded_machine.hpp"

namespace ide {

ProfileRunner::~ProfileRunner() {
  cancel();
  join();
}

void ProfileRunner::cancel() {
  std::lock_guard<std::mutex> lock(cancelLock_);
  cancelled_ = true;
  if (current_) current_->cancel();
}

void ProfileRunner::join() {
  if (worker_.joinable()) worker_.join();
}

std::vector<unsigned> ProfileRunner::defaultThreadCounts() {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  std::vector<unsigned> counts{1};
  for (unsigned n = 2; n <= cores; n *= 2) counts.push_back(n);
  return counts;
}

bool ProfileRunner::start(std::shared_ptr<const meldvm::Program> program, std::vector<std::string> args,
                          std::vector<unsigned> threads, const std::string& folder, const std::string& name) {
  if (running_.load()) return false;
  join();
  result_ = {};
  {
    std::lock_guard<std::mutex> lock(cancelLock_);
    cancelled_ = false;
  }
  running_.store(true);
  worker_ = std::thread([this, program, args = std::move(args), threads = std::move(threads), folder, name] {
    Result r;
    try {
      for (unsigned n : threads) {
        r.files.push_back(folder + "/" + name + ".j" + std::to_string(n) + ".json");
        if (!profileAt(*program, args, n, r.files.back())) {
          r.cancelled = true;
          break;
        }
      }
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    if (r.cancelled || !r.error.empty()) r.files.clear();
    result_ = std::move(r);
    running_.store(false);  // after result_: take() reads it once this is false
  });
  return true;
}

bool ProfileRunner::profileAt(const meldvm::Program& program, const std::vector<std::string>& args,
                              unsigned threads, const std::string& path) {
  meldvm::MachineOptions options;
  options.args = args;  // write-string output is not shown: the runs are for their timelines
  meldvm::ThreadedMachine machine(program, options, threads);
  machine.recordProfile();
  {
    std::lock_guard<std::mutex> lock(cancelLock_);
    if (cancelled_) return false;
    current_ = &machine;
  }
  struct Detach {  // cancel() must not reach the machine once it is gone, whatever run() did
    ProfileRunner& runner;
    ~Detach() {
      std::lock_guard<std::mutex> lock(runner.cancelLock_);
      runner.current_ = nullptr;
    }
  } detach{*this};
  machine.run();
  {
    std::lock_guard<std::mutex> lock(cancelLock_);
    if (cancelled_) return false;  // stopped part-way: no timeline to show
  }
  std::ofstream out(path, std::ios::binary);
  machine.writeProfile(out);
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
  return true;
}

std::optional<ProfileRunner::Result> ProfileRunner::take() {
  if (running_.load() || !worker_.joinable()) return std::nullopt;
  join();
  return std::move(result_);
}

}  // namespace ide
