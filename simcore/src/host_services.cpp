// The host services of the block ABI: C trampolines onto the Simulation, and the services that
// change the world (messages over links, motions, timers, colors).
#include <cstring>

#include "host_api.hpp"
#include "simcore/rng.hpp"
#include "simcore/simulation.hpp"
#include "slot_pool.hpp"

namespace simcore {

struct Simulation::Services {
  static Simulation& sim(vs_ctx* c) { return *static_cast<Simulation*>(c->host); }

  static vs_time now(vs_ctx* c) { return sim(c).queue_.now(); }
  static int faceCount(vs_ctx* c) { return sim(c).faceCount_; }
  static int send(vs_ctx* c, int face, const void* data, uint32_t size, vs_time delay) {
    return sim(c).send(c->block, face, data, size, delay);
  }
  static int sendAll(vs_ctx* c, const void* data, uint32_t size, vs_time delay) {
    Simulation& s = sim(c);
    int sent = 0;
    for (int f = 0; f < s.faceCount_; ++f) {
      if (s.world_.neighbor(c->block, f) == kNoBlock) continue;
      const int rc = s.send(c->block, f, data, size, delay);
      if (rc < 0) return rc;
      ++sent;
    }
    return sent;
  }
  static int setTimer(vs_ctx* c, vs_time delay, uint64_t tag, uint64_t* id) {
    return sim(c).setTimer(c->block, delay, tag, id);
  }
  static int cancelTimer(vs_ctx* c, uint64_t id) { return sim(c).cancelTimer(id); }
  static int setColor(vs_ctx* c, uint32_t rgb) {
    sim(c).setColor(c->block, rgb & 0xFFFFFFu);
    return VS_OK;
  }
  static uint32_t color(vs_ctx* c) { return sim(c).world_.block(c->block).color; }
  static int setValue(vs_ctx* c, int32_t v) {
    Simulation& s = sim(c);
    if (s.displayValues_.empty()) return VS_ERR_UNSUPPORTED;
    s.displayValues_[c->block] = v;
    return VS_OK;
  }
  static int move(vs_ctx* c, int face) { return sim(c).move(c->block, face); }
  static vs_block_id neighbor(vs_ctx* c, int face) {
    Simulation& s = sim(c);
    if (face < 0 || face >= s.faceCount_) return VS_NO_BLOCK;
    return s.world_.neighbor(c->block, face);
  }
  static int neighborCount(vs_ctx* c) {
    Simulation& s = sim(c);
    int n = 0;
    for (int f = 0; f < s.faceCount_; ++f) n += s.world_.neighbor(c->block, f) != kNoBlock;
    return n;
  }
  static void position(vs_ctx* c, int32_t xyz[3]) {
    const Cell& cell = sim(c).world_.block(c->block).cell;
    xyz[0] = cell.x;
    xyz[1] = cell.y;
    xyz[2] = cell.z;
  }
  static int readSensor(vs_ctx* c, int sensor, int32_t values[3]) {
    Simulation& s = sim(c);
    if (sensor != VS_SENSOR_ACCEL || s.accel_.empty()) return VS_ERR_UNSUPPORTED;
    if (!values) return VS_ERR_BAD_ARGUMENT;
    const auto& a = s.accel_[c->block];
    values[0] = a[0];
    values[1] = a[1];
    values[2] = a[2];
    return VS_OK;
  }
  static uint32_t randomU32(vs_ctx* c) { return BlockRng::next(sim(c).world_.block(c->block).rng, c->block); }
  static uint32_t randomBelow(vs_ctx* c, uint32_t bound) {
    if (bound == 0) return 0;
    return BlockRng::below(sim(c).world_.block(c->block).rng, c->block, bound);
  }
  static void trace(vs_ctx* c, const char* text) {
    Simulation& s = sim(c);
    if (!text) return;
    for (SimulationObserver* o : s.observers_) o->onBlockTrace(s, c->block, text);
  }
  static uint32_t blockCount(vs_ctx* c) { return uint32_t(sim(c).world_.blockCount()); }
  static int mobileAbove(vs_ctx* c, int32_t* mobile, double xyAngle[3]) {
    return sim(c).mobileAbove(c->block, mobile, xyAngle);
  }
  static int airJet(vs_ctx* c, int face, double power, vs_time duration) {
    return sim(c).airJet(c->block, face, power, duration);
  }
  static int faceToward(vs_ctx* c, const int32_t xyz[3]) {
    Simulation& s = sim(c);
    if (!xyz) return VS_ERR_BAD_ARGUMENT;
    const Cell& from = s.world_.block(c->block).cell;
    for (int f = 0; f < s.faceCount_; ++f)
      if (s.world_.lattice().neighborCell(from, f) == Cell{xyz[0], xyz[1], xyz[2]}) return f;
    return VS_ERR_BAD_ARGUMENT;
  }
};

const vs_host_api kHostApi = {
    VS_ABI_VERSION,
    &Simulation::Services::now,
    &Simulation::Services::faceCount,
    &Simulation::Services::send,
    &Simulation::Services::sendAll,
    &Simulation::Services::setTimer,
    &Simulation::Services::cancelTimer,
    &Simulation::Services::setColor,
    &Simulation::Services::color,
    &Simulation::Services::setValue,
    &Simulation::Services::move,
    &Simulation::Services::neighbor,
    &Simulation::Services::neighborCount,
    &Simulation::Services::position,
    &Simulation::Services::readSensor,
    &Simulation::Services::randomU32,
    &Simulation::Services::randomBelow,
    &Simulation::Services::trace,
    &Simulation::Services::blockCount,
    &Simulation::Services::faceToward,
    &Simulation::Services::mobileAbove,
    &Simulation::Services::airJet,
};

int Simulation::mobileAbove(BlockId id, std::int32_t* mobile, double xyAngle[3]) const {
  if (!physics_) return VS_ERR_UNSUPPORTED;
  if (!mobile || !xyAngle) return VS_ERR_BAD_ARGUMENT;
  const int m = physics_->mobileOver(id);
  if (m < 0) return VS_ERR_NOT_FOUND;
  const Eigen::Vector2d p = physics_->positionMm(std::size_t(m));
  *mobile = m;
  xyAngle[0] = p.x();
  xyAngle[1] = p.y();
  xyAngle[2] = physics_->angleDeg(std::size_t(m));
  return VS_OK;
}

int Simulation::airJet(BlockId id, int face, double power, SimTime duration) {
  if (!physics_) return VS_ERR_UNSUPPORTED;
  if (face < 0 || face >= faceCount_) return VS_ERR_BAD_FACE;
  if (!(power >= 0 && power <= 1) || duration < 0) return VS_ERR_BAD_ARGUMENT;
  const Lattice& lattice = world_.lattice();
  const Cell from = world_.block(id).cell, to = lattice.neighborCell(from, face);
  const Vec3 a = lattice.cellCenter(from), b = lattice.cellCenter(to);
  physics_->setJet(id, face, Eigen::Vector2d(b.x - a.x, b.y - a.y), power, queue_.now() + duration);
  wakePhysics();
  return VS_OK;
}

int Simulation::send(BlockId from, int f, const void* data, std::uint32_t size, SimTime delay) {
  if (f < 0 || f >= faceCount_) return VS_ERR_BAD_FACE;
  if (delay < 0 || (size > 0 && !data)) return VS_ERR_BAD_ARGUMENT;
  if (size > VS_MAX_MESSAGE_SIZE) return VS_ERR_TOO_LARGE;
  const BlockId to = world_.neighbor(from, f);
  if (to == kNoBlock) return VS_ERR_NO_NEIGHBOR;
  const SimTime now = queue_.now();
  FaceState& fs = faceForSending(from, f);
  const SimTime ready = now + delay;
  const SimTime busy = fs.busyUntil();
  const SimTime begin = ready > busy ? ready : busy;
  const SimTime end = begin + transmissionTime(size);
  fs.setBusyUntil(end);
  SimTime arrival = end + link_.latency;
  if (link_.jitter > 0) {
    arrival += SimTime(BlockRng::below(jitterRng_, 0xFFFFFFFEu,
                                       std::uint32_t(std::min<SimTime>(link_.jitter, 0xFFFFFFFE)) + 1));
    SimTime& last = lastArrival_[std::size_t(from) * std::size_t(faceCount_) + std::size_t(f)];
    if (arrival < last) arrival = last;  // jitter never reorders a link
    last = arrival;
  }
  const std::uint32_t slot = allocateSlot(messages_, freeMessage_);
  MessageSlot& m = messages_[slot];
  m.from = from;
  m.fromFace = std::uint8_t(f);
  m.epoch = fs.epoch;
  m.size = size;
  if (m.data.size() < size) m.data.resize(size);
  if (size) std::memcpy(m.data.data(), data, size);
  ++messagesInFlight_;
  if (fs.inFlight++ == 0) facesInFlight_[from] |= std::uint16_t(1u << f);
  ++stats_.messagesSent;
  stats_.bytesSent += size;
  const int back = world_.lattice().oppositeFace(world_.block(from).cell, f);
  schedule(arrival, to, EventKind::Message, back, slot);
  if (!messageObservers_.empty())
    for (SimulationObserver* o : messageObservers_) o->onMessageSent(*this, from, f, to, size, arrival);
  return VS_OK;
}

int Simulation::move(BlockId id, int f) {
  if (!motionRule_ && !translates_) return VS_ERR_UNSUPPORTED;
  if (f < 0 || f >= faceCount_) return VS_ERR_BAD_FACE;
  Block& b = world_.block(id);
  if (b.motion != kNoBlock) return VS_ERR_BUSY;
  // The target's rule decides where the block goes and what it needs on the way.
  MotionPlan plan;
  if (translates_) {
    const int rc = TranslationRule::translate(world_, id, f, plan);
    if (rc != VS_OK) return rc;
  } else {
    const int rc = motionRule_->plan(world_, id, f, plan);
    if (rc != VS_OK) return rc;
    // A target's rule is checked again (isFree includes the bounds): it may refuse a motion wrongly,
    // but never corrupt the grid.
    constexpr unsigned kFaceBits = (1u << kMaxMotionFaces) - 1;
    const unsigned faceMask = faceCount_ >= kMaxMotionFaces ? kFaceBits : (1u << faceCount_) - 1;
    if (plan.pivotFace >= faceCount_ || (plan.sweptFromFaces & ~faceMask) || (plan.sweptToFaces & ~faceMask))
      return VS_ERR_BAD_FACE;
    bool free = world_.isFree(plan.to);
    forEachSweptCell(world_.lattice(), b.cell, plan.to, plan.sweptFromFaces, plan.sweptToFaces,
                     [&](const Cell& c) { free = free && world_.isFree(c); });
    if (!free) return VS_ERR_CELL_OCCUPIED;
  }
  if (motionCheck_) [[unlikely]] {
    const int rc = motionCheck_->check(*this, id, plan.to);
    if (rc != VS_OK) return rc;
  }
  const Cell& to = plan.to;
  breakLinks(id);  // while the block is still settled, so its neighbors are found
  const std::uint32_t slot = allocateSlot(motions_, freeMotion_);
  MotionSlot& m = motions_[slot];
  m.from = b.cell;
  m.end = queue_.now() + motionDuration_;
  m.sweptFromFaces = plan.sweptFromFaces;
  m.sweptToFaces = plan.sweptToFaces;
  m.pivotFace = std::int8_t(plan.pivotFace);
  world_.reserve(m.from, id);
  world_.reserve(to, id);
  if (m.sweptFromFaces | m.sweptToFaces) [[unlikely]] setSweptCells(m, to, id);
  b.cell = to;
  b.motion = slot;
  ++stats_.motionsStarted;
  schedule(m.end, id, EventKind::MotionEnd, f, slot);
  if (!observers_.empty())
    for (SimulationObserver* o : observers_) o->onMotionStarted(*this, id, m.from, to, m.end);
  return VS_OK;
}

int Simulation::setTimer(BlockId id, SimTime delay, std::uint64_t tag, std::uint64_t* timerId) {
  if (delay < 0) return VS_ERR_BAD_ARGUMENT;
  if (!timerId) {
    schedule(queue_.now() + delay, id, EventKind::Timer, 0, tag);
    return VS_OK;
  }
  const std::uint32_t slot = allocateSlot(timers_, freeTimer_);
  TimerSlot& t = timers_[slot];
  t.generation |= 1u;  // odd: pending (a released slot's generation is even)
  t.tag = tag;
  const std::uint64_t fullId = (std::uint64_t(t.generation) << 32) | slot;
  if (timerId) *timerId = fullId;
  schedule(queue_.now() + delay, id, EventKind::Timer, kTimerHasSlot, fullId);
  return VS_OK;
}

int Simulation::cancelTimer(std::uint64_t timerId) {
  const std::uint32_t slot = std::uint32_t(timerId);
  if (timerId == 0 || slot >= timers_.size()) return VS_ERR_NOT_FOUND;
  TimerSlot& t = timers_[slot];
  if (!t.pending() || t.generation != std::uint32_t(timerId >> 32)) return VS_ERR_NOT_FOUND;
  // The slot stays reserved until its event comes up, so the id cannot be reused before then.
  ++t.generation;
  ++stats_.timersCancelled;
  return VS_OK;
}

void Simulation::setColor(BlockId id, std::uint32_t rgb) {
  world_.block(id).color = rgb;
  if (!observers_.empty())
    for (SimulationObserver* o : observers_) o->onColorChanged(*this, id, rgb);
}

Simulation::FaceState& Simulation::faceForSending(BlockId b, int f) {
  if (faceGroup_[b] == kNoBlock) {
    faceGroup_[b] = std::uint32_t(faces_.size() / std::size_t(faceCount_));
    faces_.resize(faces_.size() + std::size_t(faceCount_));
  }
  return face(b, f);
}

void Simulation::releaseMessage(std::uint32_t slot) { releaseSlot(messages_, freeMessage_, slot); }
void Simulation::releaseMotion(std::uint32_t slot) { releaseSlot(motions_, freeMotion_, slot); }

void Simulation::releaseTimer(std::uint32_t slot) { releaseSlot(timers_, freeTimer_, slot); }

void Simulation::setSweptCells(const MotionSlot& m, const Cell& to, BlockId id) {
  forEachSweptCell(world_.lattice(), m.from, to, m.sweptFromFaces, m.sweptToFaces, [&](const Cell& c) {
    if (id == kNoBlock)
      world_.clearCell(c);
    else
      world_.reserve(c, id);
  });
}

}  // namespace simcore
