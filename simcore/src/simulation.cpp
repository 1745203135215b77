#include "simcore/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "simcore/rng.hpp"
#include "slot_pool.hpp"

namespace simcore {

namespace {
constexpr std::size_t kPrefetchFar = 12, kPrefetchMid = 6;
}  // namespace

Simulation::Simulation(const TargetSpec& target, GridSize size, const SimulationConfig& config)
    : target_(target),
      config_(config),
      link_(target.link),
      motionRule_(target.motionRule),
      translates_(!target.motionRule && target.canTranslate),
      motionDuration_(config.motionDuration >= 0 ? config.motionDuration : target.motionDuration),
      world_(target.makeLattice(), size),
      faceCount_(world_.faceCount()),
      queue_(makeFutureEventSet(config.fes)) {
  if (faceCount_ > 16) throw std::logic_error("lattices with more than 16 faces are not supported");
  if (config.linkRateBitsPerSecond > 0) link_.rateBitsPerSecond = config.linkRateBitsPerSecond;
  if (config.linkLatency >= 0) link_.latency = config.linkLatency;
  if (config.linkJitter >= 0) link_.jitter = config.linkJitter;
  jitterRng_ = BlockRng::initialState(config.seed, 0xFFFFFFFEu);
}

Simulation::~Simulation() = default;

const char* Simulation::fesName() const { return const_cast<EventQueue&>(queue_).futureEventSet().name(); }

BlockId Simulation::addBlock(const Cell& cell, std::uint32_t color) {
  if (started_) throw std::logic_error("blocks can only be added before the simulation starts");
  const BlockId id = world_.addBlock(cell, color);
  if (id == kNoBlock) return id;
  world_.block(id).rng = BlockRng::initialState(config_.seed, id);
  return id;
}

void Simulation::setBlockCode(const vs_blockcode* code) {
  if (started_) throw std::logic_error("the block code must be set before the simulation starts");
  if (code && !vs_abi_supported(code->abi_version))
    throw std::runtime_error("block code '" + std::string(code->name ? code->name : "?") +
                             "' was built for block ABI version " + std::to_string(code->abi_version) +
                             ", this simulator speaks versions " + std::to_string(VS_ABI_OLDEST_VERSION) +
                             " to " + std::to_string(VS_ABI_VERSION));
  code_ = code;
}

void Simulation::checkExternalEvent(BlockId block, SimTime time, const char* what) const {
  if (block >= world_.blockCount())
    throw std::invalid_argument(std::string(what) + " for block " + std::to_string(block) +
                                ", but the world has " + std::to_string(world_.blockCount()) + " blocks");
  if (time < queue_.now())
    throw std::invalid_argument(std::string(what) + " at " + formatTime(time) + ", before the current time " +
                                formatTime(queue_.now()));
}

void Simulation::scheduleTap(BlockId block, SimTime time) {
  checkExternalEvent(block, time, "tap");
  schedule(time, block, EventKind::Tap, 0, 0);
}

void Simulation::scheduleAccel(BlockId block, SimTime time, std::int32_t x, std::int32_t y, std::int32_t z) {
  checkExternalEvent(block, time, "accelerometer reading");
  const std::uint32_t slot = allocateSlot(sensorReadings_, freeSensorReading_);
  sensorReadings_[slot].values = {x, y, z};
  schedule(time, block, EventKind::Sensor, 0, slot);
}

void Simulation::startIfNeeded() {
  if (started_) return;
  started_ = true;
  const std::size_t n = world_.blockCount();
  faces_.clear();
  faceGroup_.assign(n, kNoBlock);
  facesInFlight_.assign(n, 0);
  if (link_.jitter > 0) lastArrival_.assign(n * std::size_t(faceCount_), 0);
  if (target_.hasAccelerometer) accel_.assign(n, {0, 0, -1});
  if (target_.hasDisplayValue) displayValues_.assign(n, 0);
  // Each block's state is aligned like any C object of its size could need: to 16 bytes, or to its
  // size rounded up to a power of two when that is smaller (a 2-byte state takes 2 bytes, not 16).
  stateSize_ = 0;
  if (code_ && code_->state_size) {
    std::uint32_t stride = 1;
    while (stride < code_->state_size && stride < 16) stride <<= 1;
    stateSize_ = stride < 16 ? stride : (code_->state_size + 15u) & ~15u;
  }
  if (stateSize_) {
    stateStorage_.assign(n * stateSize_ + 16, 0);
    unsigned char* raw = stateStorage_.data();
    stateBase_ = raw + ((16 - (reinterpret_cast<std::uintptr_t>(raw) & 15)) & 15);
  }
  for (BlockId id = 0; id < n; ++id) schedule(0, id, EventKind::Start, 0, 0, /*bypassFifo=*/true);
  if (physics_) announceCoverage();  // the blocks under a mobile at the start hear of it first thing
}

void Simulation::setPhysics(std::unique_ptr<Physics> physics) {
  if (started_) throw std::logic_error("the physics must be set before the simulation starts");
  if (physics && !target_.canTranslate)
    throw std::invalid_argument("mobiles and air jets need a surface of Smart Blocks, not " + target_.name);
  physics_ = std::move(physics);
}

void Simulation::announceCoverage() {
  for (const Physics::CoverChange& c : physics_->coverChanges())
    schedule(queue_.now(), c.block, EventKind::Mobile, c.arrived ? 1 : 0, std::uint64_t(c.mobile));
}

void Simulation::wakePhysics() {
  if (physicsScheduled_) return;
  physicsScheduled_ = true;
  schedule(queue_.now() + physics_->model().step, 0, EventKind::PhysicsStep, 0, 0);
}

void Simulation::stepPhysics() {
  const bool goOn = physics_->step(queue_.now());
  announceCoverage();
  for (SimulationObserver* o : observers_) o->onPhysicsStep(*this);
  physicsScheduled_ = false;
  if (goOn) wakePhysics();
}

SimTime Simulation::transmissionTime(std::uint32_t size) const {
  return SimTime(double(size) * 8.0 * 1e9 / link_.rateBitsPerSecond + 0.5);
}

void Simulation::removeObserver(SimulationObserver* observer) {
  for (auto* list : {&observers_, &eventObservers_, &messageObservers_})
    list->erase(std::remove(list->begin(), list->end(), observer), list->end());
}

const Statistics& Simulation::statistics() const {
  stats_.simulatedTime = queue_.now();
  stats_.maxQueueSize = queue_.maxSize();
  stats_.wallSeconds = wallSeconds_;
  return stats_;
}

// Always inlined: GCC infers that a function whose only effect is a prefetch is pure, and then
// deletes every call to it.
[[gnu::always_inline]] inline void Simulation::prefetchRecords(const Event& e) const {
  const BlockId id = e.block;
  __builtin_prefetch(&world_.block(id));
  world_.prefetchAlive(id);
  if (stateSize_) __builtin_prefetch(stateBase_ + std::size_t(id) * stateSize_);
  const std::uint32_t slot = std::uint32_t(e.arg);
  if (e.kind == EventKind::Timer && e.face == kTimerHasSlot && slot < timers_.size())
    __builtin_prefetch(&timers_[slot]);
  if (e.kind == EventKind::Message && slot < messages_.size()) __builtin_prefetch(&messages_[slot]);
  if (e.kind == EventKind::MotionEnd && slot < motions_.size()) __builtin_prefetch(&motions_[slot]);
}

[[gnu::always_inline]] inline void Simulation::prefetchCells(const Event& e) const {
  world_.prefetchAround(world_.block(e.block).cell);
}

RunStatus Simulation::run(SimTime until, std::uint64_t maxEvents) {
  startIfNeeded();
  const auto wallStart = std::chrono::steady_clock::now();
  RunStatus status = RunStatus::Idle;
  Event e;
  std::uint64_t processed = 0;
  for (;;) {
    if (processed == maxEvents) {
      status = RunStatus::EventLimit;
      break;
    }
    if (!queue_.popUntil(until, e)) {
      if (!queue_.empty()) {
        status = RunStatus::TimeLimit;
        queue_.advanceTo(until);
      } else if (until != kTimeInfinity) {
        queue_.advanceTo(until);
      }
      break;
    }
    ++processed;
    // Blocks are visited in time order, i.e. at random in memory. A two-stage software pipeline
    // loads what upcoming events will touch, so the cache misses overlap with the work of this one:
    // far ahead the block's own records, then the grid around it.
    if (const Event* a = queue_.peekAhead(kPrefetchFar)) prefetchRecords(*a);
    if (const Event* a = queue_.peekAhead(kPrefetchMid)) prefetchCells(*a);
    dispatch(e);
  }
  wallSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  return status;
}

Vec3 Simulation::position(BlockId id) const {
  const Block& b = world_.block(id);
  const Lattice& lat = world_.lattice();
  if (b.motion == kNoBlock) return lat.cellCenter(b.cell);
  const MotionSlot& m = motions_[b.motion];
  const SimTime start = m.end - motionDuration_;
  double f = m.end > start ? double(queue_.now() - start) / double(m.end - start) : 1.0;
  f = std::clamp(f, 0.0, 1.0);
  const bool turns = m.pivotFace >= 0;
  const Vec3 pivot = turns ? lat.cellCenter(lat.neighborCell(m.from, m.pivotFace)) : Vec3{};
  return motionPoint(lat.cellCenter(m.from), lat.cellCenter(b.cell), turns ? &pivot : nullptr, f);
}

}  // namespace simcore
