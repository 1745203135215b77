#include "kernel_loop.hpp"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>

#include "meldvm/dump.hpp"

namespace ide {

namespace {

// Events per slice: small enough that commands are seen within milliseconds, large enough that
// the loop's own work stays negligible next to the kernel's.
constexpr std::uint64_t kSliceEvents = 4096;
// Snapshots at most this often while running (the GUI draws at up to 60 frames per second).
constexpr std::chrono::milliseconds kPublishEvery{16};

SessionInfo describe(const vsim::Session& s) {
  SessionInfo info;
  const simcore::WorldDescription& w = s.world();
  const simcore::Simulation& sim = s.simulation();
  info.worldPath = w.path;
  info.codePath = s.codePath();
  info.codeName = s.codeName();
  info.targetName = sim.target().name;
  info.shape = shapeOfTarget(info.targetName);
  info.blockSizeMm = blockSizeOf(w, sim.target().blockSizeMm);
  info.grid = sim.world().size();
  info.faceNames = sim.target().faceNames;
  info.blockCount = sim.world().blockCount();
  info.meld = s.isMeld();
  info.camera = parseViewPoint(w.camera);
  info.spotlight = parseViewPoint(w.spotlight);
  return info;
}

}  // namespace

KernelLoop::KernelLoop(const vsim::Options& options, std::uint64_t sessionId, std::ostream& diagnostics,
                       bool recordDerivations)
    : sessionId_(sessionId) {
  vsim::SessionStreams streams;
  streams.programOutput = &consoleStream_;
  streams.diagnostics = &diagnostics;
  session_ = std::make_unique<vsim::Session>(options, streams);
  info_ = describe(*session_);
  // By default the console shows the programs' own trace lines (the C BlockCodes' trace service;
  // a Meld program's output comes through programOutput).
  trace_.emplace(consoleStream_, simcore::parseTraceFilter("kinds=trace"), simcore::TraceFormat::Text);
  session_->simulation().addObserver(&*trace_);
  if (recordDerivations && session_->meld()) {
    derivations_ = std::make_unique<meldvm::DerivationLog>();
    session_->meld()->recordDerivations(derivations_.get());
  }
  publish();
  thread_ = std::thread([this] { threadMain(); });
}

KernelLoop::~KernelLoop() {
  post(Command{Command::Quit});
  thread_.join();
  if (history_) session_->simulation().removeObserver(history_.get());
  if (derivations_) session_->meld()->recordDerivations(nullptr);
}

void KernelLoop::post(Command c) {
  {
    std::lock_guard lock(mutex_);
    commands_.push_back(std::move(c));
  }
  wake_.notify_one();
}

std::shared_ptr<const WorldSnapshot> KernelLoop::snapshot() const {
  snapshotWanted_.store(true, std::memory_order_relaxed);
  std::lock_guard lock(mutex_);
  return latest_;
}

std::shared_ptr<const WorldSnapshot> KernelLoop::waitFor(
    const std::function<bool(const WorldSnapshot&)>& done, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  const auto deadline = Clock::now() + timeout;
  while (!done(*latest_))
    if (published_.wait_until(lock, deadline) == std::cv_status::timeout && !done(*latest_)) return nullptr;
  return latest_;
}

void KernelLoop::threadMain() {
  std::vector<Command> batch;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      // Paused or over: sleep until told something. Running: only look.
      if (state_ != RunState::Running) wake_.wait(lock, [&] { return !commands_.empty(); });
      batch.swap(commands_);
    }
    for (const Command& c : batch)
      if (!apply(c)) return;
    const bool changed = !batch.empty();
    batch.clear();
    if (state_ == RunState::Running) runSlice();
    if (changed || state_ != RunState::Running ||
        (snapshotWanted_.load(std::memory_order_relaxed) && Clock::now() - lastPublish_ >= kPublishEvery))
      publish();
  }
}

bool KernelLoop::apply(const Command& c) {
  simcore::Simulation& sim = session_->simulation();
  const bool over = state_ == RunState::Finished || state_ == RunState::Failed;
  switch (c.kind) {
    case Command::Quit:
      return false;
    case Command::Run:
      if (over) break;
      state_ = RunState::Running;
      speed_ = c.speed;
      until_ = c.until;
      pacedFrom_ = sim.now();
      pacedSince_ = Clock::now();
      break;
    case Command::Pause:
      if (!over) state_ = RunState::Paused;
      break;
    case Command::Step:
      if (over) break;
      state_ = RunState::Paused;
      try {
        sim.step();
      } catch (const std::exception& e) {
        error_ = e.what();
        state_ = RunState::Failed;
      }
      finishIfOver();
      break;
    case Command::Select:
      selected_ = c.block;
      followHistory();
      break;
    case Command::History:
      historyWanted_ = c.on;
      followHistory();
      break;
    case Command::Why:
      answerWhy(c);
      break;
    case Command::Remove:
      removeBlock(c.block);
      break;
    case Command::Add:
      addBlock(c);
      break;
    case Command::SaveWorld:
      saveWorld(c.fact);
      break;
    case Command::Tap:
      // A tap after the end starts the run again (VisibleSim lets one tap a block at any time).
      if (!sim.target().hasTap) {
        console_.push(sim.target().name + " blocks have no tap sensor.");
        break;
      }
      if (state_ == RunState::Failed || c.block >= sim.world().blockCount() || !sim.world().isAlive(c.block))
        break;
      sim.scheduleTap(c.block, sim.now());
      if (state_ == RunState::Finished) state_ = RunState::Paused;
      break;
    case Command::Trace:
      sim.removeObserver(&*trace_);
      trace_.emplace(consoleStream_, c.filter, simcore::TraceFormat::Text);
      sim.addObserver(&*trace_);
      break;
  }
  return true;
}

void KernelLoop::runSlice() {
  simcore::Simulation& sim = session_->simulation();
  simcore::SimTime bound = until_;
  if (speed_ > 0) {
    const double wallNs =
        double(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - pacedSince_).count());
    const double paced = double(pacedFrom_) + speed_ * wallNs;
    bound = std::min<simcore::SimTime>(
        bound, paced >= double(simcore::kTimeInfinity) ? simcore::kTimeInfinity : simcore::SimTime(paced));
  }
  simcore::RunStatus status;
  try {
    status = sim.run(bound, kSliceEvents);
  } catch (const std::exception& e) {
    error_ = e.what();
    state_ = RunState::Failed;
    return;
  }
  finishIfOver();
  if (state_ != RunState::Running || status == simcore::RunStatus::EventLimit) return;
  if (bound >= until_) {
    state_ = RunState::Paused;  // reached the requested time
    return;
  }
  // Paced and ahead of the wall clock: wait a frame, or until a command comes.
  std::unique_lock lock(mutex_);
  wake_.wait_for(lock, std::chrono::milliseconds(8), [&] { return !commands_.empty(); });
}

void KernelLoop::finishIfOver() {
  if (state_ == RunState::Failed) return;
  if (!session_->programError().empty()) {
    error_ = "Meld program failed: " + session_->programError();
    state_ = RunState::Failed;
  } else if (session_->simulation().pendingEvents() == 0) {
    state_ = RunState::Finished;
  }
}

void KernelLoop::publish() {
  const simcore::Simulation& sim = session_->simulation();
  const simcore::World& world = sim.world();
  auto snap = std::make_shared<WorldSnapshot>();
  snap->serial = ++serial_;
  snap->session = sessionId_;
  snap->now = sim.now();
  snap->events = sim.statistics().eventsProcessed;
  snap->eventsPerSecond = sim.statistics().eventsPerSecond();
  snap->pendingEvents = sim.pendingEvents();
  snap->state = state_;
  snap->fingerprint = sim.fingerprint();
  snap->error = error_;
  const std::size_t n = world.blockCount();
  snap->positions.resize(n);
  snap->colors.resize(n);
  snap->alive.resize(n);
  const std::array<float, 3>& size = info_.blockSizeMm;
  for (simcore::BlockId b = 0; b < n; ++b) {
    const simcore::Vec3 p = sim.position(b);
    snap->positions[b] = {(float(p.x) + 0.5f) * size[0], (float(p.y) + 0.5f) * size[1],
                          (float(p.z) + 0.5f) * size[2]};
    snap->colors[b] = world.block(b).color;
    snap->alive[b] = world.isAlive(b);
  }
  snap->selected = details(selected_);
  if (history_) {
    history_->flush();
    snap->selected.history.assign(history_->entries().begin(), history_->entries().end());
  }
  snap->why = why_;
  {
    std::lock_guard lock(mutex_);
    latest_ = std::move(snap);
  }
  published_.notify_all();
  lastPublish_ = Clock::now();
  snapshotWanted_.store(false, std::memory_order_relaxed);
}

void KernelLoop::followHistory() {
  simcore::Simulation& sim = session_->simulation();
  const bool wanted = historyWanted_ && selected_ < sim.world().blockCount();
  if (history_ && (!wanted || history_->block() != selected_)) {
    sim.removeObserver(history_.get());
    history_.reset();
  }
  if (wanted && !history_) {
    history_ = std::make_unique<BlockHistory>(*session_, selected_);
    sim.addObserver(history_.get());
  }
}

void KernelLoop::removeBlock(simcore::BlockId block) {
  simcore::Simulation& sim = session_->simulation();
  if (state_ == RunState::Running) return console_.push("Pause the run before removing a block.");
  if (state_ == RunState::Failed) return;
  if (block >= sim.world().blockCount() || !sim.world().isAlive(block)) return;
  sim.removeBlock(block);  // its links break; its neighbours are told (events at the current time)
  if (state_ == RunState::Finished && sim.pendingEvents() > 0) state_ = RunState::Paused;
  console_.push("Removed block " + std::to_string(block) + " at " + simcore::formatTime(sim.now()) + ".");
}

void KernelLoop::addBlock(const Command& c) {
  simcore::Simulation& sim = session_->simulation();
  if (state_ == RunState::Running) return console_.push("Pause the run before adding a block.");
  if (state_ == RunState::Failed) return;
  simcore::World& world = sim.world();
  simcore::Cell cell = c.cell;
  if (c.block != simcore::kNoBlock) {  // the first free cell next to that block, in face order
    if (c.block >= world.blockCount() || !world.isAlive(c.block)) return;
    bool found = false;
    for (int f = 0; f < world.faceCount() && !found; ++f) {
      cell = world.lattice().neighborCell(world.block(c.block).cell, f);
      found = world.isFree(cell) && world.lattice().isValidCell(cell);
    }
    if (!found) return console_.push("Block " + std::to_string(c.block) + " has no free cell around it.");
  }
  const simcore::BlockId id = sim.addBlockWhileRunning(cell, sim.target().defaultColor);
  const std::string where =
      "(" + std::to_string(cell.x) + ", " + std::to_string(cell.y) + ", " + std::to_string(cell.z) + ")";
  if (id == simcore::kNoBlock)
    return console_.push("Cannot add a block at " + where + ": outside the grid or taken.");
  if (state_ == RunState::Finished) state_ = RunState::Paused;
  console_.push("Added block " + std::to_string(id) + " at " + where + ", " + simcore::formatTime(sim.now()) +
                ".");
}

void KernelLoop::saveWorld(const std::string& path) {
  const simcore::Simulation& sim = session_->simulation();
  std::ofstream out(path, std::ios::binary);
  simcore::WorldDescription now = session_->world();
  now.seed = sim.seed();
  // The block program that ran, by an absolute path: the file may be saved in another folder.
  const std::string code = std::filesystem::absolute(session_->codePath()).lexically_normal().string();
  (session_->isMeld() ? now.program : now.code) = code;
  (session_->isMeld() ? now.code : now.program).clear();
  if (out) simcore::exportWorldXml(sim, now, out);
  out.close();
  if (!out)
    console_.push("Cannot write the world to '" + path + "'.");
  else
    console_.push("Saved the world as it is at " + simcore::formatTime(sim.now()) + " to " + path + ".");
}

void KernelLoop::answerWhy(const Command& c) {
  auto r = std::make_shared<WhyResult>();
  r->request = c.request;
  r->block = c.block;
  r->fact = c.fact;
  if (c.block == simcore::kNoBlock && session_->meld()) {  // a spec as the user typed it
    try {
      const meldvm::FactAt f = meldvm::parseFactSpec(c.fact, *session_->meldProgram());
      r->block = f.node;
      r->fact = f.text;
    } catch (const std::invalid_argument& e) {
      r->error = e.what();
      why_ = std::move(r);
      return;
    }
  }
  if (!session_->meld())
    r->error = "Only the facts of a Meld program have derivations.";
  else if (!derivations_)
    r->error = "Derivations are not recorded: turn on Run > Record derivations (the run starts again).";
  else
    r->lines = meldvm::whyTree(*derivations_, meldvm::FactAt{meldvm::NodeId(r->block), r->fact});
  if (r->error.empty() && r->lines.empty())
    r->error = "No record of " + r->fact + " on block " + std::to_string(r->block) + ".";
  why_ = std::move(r);
}

BlockDetails KernelLoop::details(simcore::BlockId id) {
  BlockDetails d;
  simcore::Simulation& sim = session_->simulation();
  const simcore::World& world = sim.world();
  if (id >= world.blockCount()) return d;
  const simcore::Block& b = world.block(id);
  d.id = id;
  d.cell = b.cell;
  d.color = b.color;
  d.alive = world.isAlive(id);
  d.moving = b.motion != simcore::kNoBlock;
  for (int f = 0; f < world.faceCount(); ++f)
    d.neighbors.emplace_back(info_.faceNames[std::size_t(f)], world.neighbor(id, f));
  if (const meldvm::BlockRuntime* meld = session_->meld()) {
    const meldvm::Database& db = meld->machine().database();
    for (meldvm::PredicateFacts& g : meldvm::nodeFacts(db, meldvm::NodeId(id))) {
      const meldvm::PredicateDesc& p = db.predicates()[g.pred];
      d.facts.push_back(FactGroup{p.name, p.persistent(), std::move(g.lines)});
    }
  } else if (d.alive) {
    d.info = sim.blockInfo(id);
  }
  return d;
}

}  // namespace ide
