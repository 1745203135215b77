#include "sim_controller.hpp"

#include <sstream>

#include "kernel_loop.hpp"
#include "simcore/trace.hpp"

namespace ide {

const char* runStateName(RunState s) {
  switch (s) {
    case RunState::Paused:
      return "paused";
    case RunState::Running:
      return "running";
    case RunState::Finished:
      return "finished";
    case RunState::Failed:
      return "failed";
  }
  return "?";
}

SimController::SimController() = default;

SimController::~SimController() { close(); }

void SimController::close() { loop_.reset(); }

bool SimController::open(const vsim::Options& options) {
  close();
  options_ = options;
  openError_.clear();
  openErrorCode_ = 0;
  diagnostics_.clear();
  std::ostringstream diagnostics;
  try {
    loop_ = std::make_unique<KernelLoop>(options_, ++sessionCount_, diagnostics, recordDerivations_);
    info_ = loop_->info();
    if (history_) setHistory(true);
  } catch (const vsim::SessionError& e) {
    openError_ = e.message;
    openErrorCode_ = e.code;
  } catch (const std::exception& e) {  // out of memory building a huge world, ...
    openError_ = e.what();
    openErrorCode_ = vsim::kExitRuntime;
  }
  diagnostics_ = diagnostics.str();
  return loop_ != nullptr;
}

void SimController::run(double speed) { runUntil(simcore::kTimeInfinity, speed); }

void SimController::runUntil(simcore::SimTime t, double speed) {
  if (!loop_) return;
  Command c{Command::Run};
  c.speed = speed;
  c.until = t;
  loop_->post(c);
}

void SimController::pause() { post(Command{Command::Pause}); }
void SimController::step() { post(Command{Command::Step}); }

void SimController::post(Command c) {
  if (loop_) loop_->post(std::move(c));
}

// A command about one block.
namespace {
Command aboutBlock(Command::Kind kind, simcore::BlockId block) {
  Command c{kind};
  c.block = block;
  return c;
}
}  // namespace

void SimController::select(simcore::BlockId block) { post(aboutBlock(Command::Select, block)); }
void SimController::removeBlock(simcore::BlockId block) { post(aboutBlock(Command::Remove, block)); }
void SimController::addBlockNextTo(simcore::BlockId block) { post(aboutBlock(Command::Add, block)); }
void SimController::tap(simcore::BlockId block) { post(aboutBlock(Command::Tap, block)); }

void SimController::setHistory(bool on) {
  history_ = on;
  Command c{Command::History};
  c.on = on;
  post(c);
}

std::uint64_t SimController::why(simcore::BlockId block, const std::string& fact) {
  if (!loop_) return 0;
  Command c = aboutBlock(Command::Why, block);
  c.fact = fact;
  c.request = ++whyRequests_;
  post(c);
  return c.request;
}

void SimController::addBlock(const simcore::Cell& cell) {
  Command c{Command::Add};
  c.cell = cell;
  post(c);
}

void SimController::saveWorld(const std::string& path) {
  Command c{Command::SaveWorld};
  c.fact = path;
  post(c);
}

void SimController::setTraceFilter(const std::string& filter) {
  Command c{Command::Trace};
  c.filter = simcore::parseTraceFilter(filter.empty() ? std::string("kinds=trace") : filter);
  post(c);
}

std::shared_ptr<const WorldSnapshot> SimController::snapshot() const {
  return loop_ ? loop_->snapshot() : nullptr;
}

std::shared_ptr<const WorldSnapshot> SimController::waitFor(
    const std::function<bool(const WorldSnapshot&)>& done, std::chrono::milliseconds timeout) const {
  return loop_ ? loop_->waitFor(done, timeout) : nullptr;
}

std::shared_ptr<const WorldSnapshot> SimController::runToAndWait(simcore::SimTime t) {
  if (!loop_) return nullptr;
  // Only a snapshot made after the command counts: the one before may already look "there" (a
  // paused run at time 0 when t is 0) without the events at t having run.
  const std::uint64_t before = loop_->snapshot()->serial;
  runUntil(t);
  auto there = [&](const WorldSnapshot& s) {
    return s.serial > before && (s.state == RunState::Finished || s.state == RunState::Failed ||
                                 (s.state == RunState::Paused && s.now >= t));
  };
  std::shared_ptr<const WorldSnapshot> snap;
  while (!(snap = waitFor(there, std::chrono::seconds(1)))) {
  }
  return snap;
}

std::vector<std::string> SimController::takeConsoleLines() {
  return loop_ ? loop_->takeConsoleLines() : std::vector<std::string>{};
}

}  // namespace ide
