// Profiling from the IDE (ide/core/profile_runner): the runs write one profile per thread count,
// and a run in progress stops when asked, or when the runner goes away with the window, instead
// of holding the IDE open until it ends. No Qt: it runs under the tsan preset too.
#define BOOST_TEST_MODULE ide_profile_runner
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "meld_program.hpp"
#include "profile_runner.hpp"

namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

struct Folder {
  fs::path path = fs::temp_directory_path() / ("ide-profile-runner-" + std::to_string(::getpid()));
  Folder() { fs::create_directories(path); }
  ~Folder() { fs::remove_all(path); }
};

// Counts to `limit` on one node: one rule firing per step, so a large limit runs for minutes.
std::shared_ptr<const meldvm::Program> counter(const Folder& f, long limit) {
  const fs::path source = f.path / "count.meld";
  std::ofstream(source) << "type linear count(node, int).\ncount(@0, 0).\n"
                        << "count(A, N), N < " << limit << " -o count(A, N + 1).\n";
  return vsim::loadMeldProgram(source.string(), {}, nullptr, /*robots=*/false);
}

// Waits for the runs to end; false after `limit`.
bool endsWithin(const ide::ProfileRunner& runner, std::chrono::seconds limit) {
  const Clock::time_point deadline = Clock::now() + limit;
  while (runner.running())
    if (Clock::now() > deadline)
      return false;
    else
      std::this_thread::sleep_for(5ms);
  return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(writes_one_profile_per_thread_count) {
  Folder f;
  ide::ProfileRunner runner;
  BOOST_TEST(runner.start(counter(f, 1000), {}, {1, 2}, f.path.string(), "count"));
  BOOST_TEST(endsWithin(runner, 120s));
  const std::optional<ide::ProfileRunner::Result> r = runner.take();
  BOOST_TEST_REQUIRE(r.has_value());
  BOOST_TEST(r->error == "");
  BOOST_TEST(!r->cancelled);
  BOOST_TEST_REQUIRE(r->files.size() == 2u);
  BOOST_TEST(r->files[1] == (f.path / "count.j2.json").string());
  for (const std::string& file : r->files) BOOST_TEST(fs::file_size(file) > 0u);
  BOOST_TEST(!runner.take().has_value());  // handed over once
}

BOOST_AUTO_TEST_CASE(cancel_stops_a_long_run_at_once) {
  Folder f;
  ide::ProfileRunner runner;
  // Two billion steps: minutes (over two on this machine) if nothing stopped it.
  BOOST_TEST(runner.start(counter(f, 2000000000), {}, {2, 1}, f.path.string(), "count"));
  std::this_thread::sleep_for(200ms);
  BOOST_TEST(runner.running());
  BOOST_TEST(!runner.start(counter(f, 10), {}, {1}, f.path.string(), "other"));  // one at a time
  runner.cancel();
  BOOST_TEST(endsWithin(runner, 10s));
  const std::optional<ide::ProfileRunner::Result> r = runner.take();
  BOOST_TEST_REQUIRE(r.has_value());
  BOOST_TEST(r->cancelled);
  BOOST_TEST(r->error == "");
  BOOST_TEST(r->files.empty());
  BOOST_TEST(!fs::exists(f.path / "count.j1.json"));  // the second thread count never ran
  // A cancelled runner runs again.
  BOOST_TEST(runner.start(counter(f, 100), {}, {1}, f.path.string(), "again"));
  BOOST_TEST(endsWithin(runner, 120s));
  const std::optional<ide::ProfileRunner::Result> again = runner.take();
  BOOST_TEST_REQUIRE(again.has_value());
  BOOST_TEST(again->error == "");
  BOOST_TEST(again->files.size() == 1u);
}

BOOST_AUTO_TEST_CASE(closing_during_a_run_does_not_wait_for_it) {
  Folder f;
  const Clock::time_point start = Clock::now();
  {
    ide::ProfileRunner runner;
    BOOST_TEST(runner.start(counter(f, 2000000000), {}, {1, 2}, f.path.string(), "count"));
    std::this_thread::sleep_for(200ms);
    BOOST_TEST(runner.running());
  }  // the window closes
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  BOOST_TEST(seconds < 10.0);
}
