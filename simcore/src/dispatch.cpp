// Event dispatch: turns popped kernel events into world changes and block-program callbacks.
#include <cstdio>
#include <cstring>
#include <string>

#include "host_api.hpp"
#include "simcore/rng.hpp"
#include "simcore/simulation.hpp"
#include "slot_pool.hpp"

namespace simcore {

void Simulation::deliver(BlockId block, const vs_event& ev) {
  if (!code_ || !code_->event) return;
  vs_ctx ctx{&kHostApi, this, block, blockState(block), code_->user};
  code_->event(&ctx, &ev);
}

std::string Simulation::blockInfo(BlockId id) {
  // The per-block state exists once the run has started; before that there is nothing to describe.
  if (!code_ || !code_->info || !started_ || id >= world_.blockCount()) return {};
  vs_ctx ctx{&kHostApi, this, id, blockState(id), code_->user};
  char text[256];
  text[0] = '\0';
  const int n = code_->info(&ctx, text, sizeof text);
  if (n < int(sizeof text)) return std::string(text, strnlen(text, sizeof text));
  std::string longer(std::size_t(n) + 1, '\0');  // the text did not fit: ask again with room for it
  code_->info(&ctx, longer.data(), longer.size());
  longer.resize(strnlen(longer.c_str(), longer.size()));
  return longer;
}

// A physics step is addressed to block 0 but belongs to no block (it runs even if block 0 is gone);
// handled inside dispatch's switch, so that worlds without physics pay no test for it.
void Simulation::dispatchPhysicsStep(const Event& e) {
  ++stats_.eventsProcessed;
  ++stats_.eventsByKind[std::size_t(e.kind)];
  fingerprint_.add(e.time, e.block, e.kind);
  stepPhysics();
}

void Simulation::dispatch(const Event& e) {
  // Only the compact alive array is read here: neighbor notifications need nothing else of the block.
  if (!world_.isAlive(e.block)) {
    if (e.kind == EventKind::PhysicsStep) return dispatchPhysicsStep(e);
    // Events for a removed block are discarded unseen; only their slots are given back.
    if (e.kind == EventKind::Message) releaseMessage(std::uint32_t(e.arg));
    if (e.kind == EventKind::MotionEnd) releaseMotion(std::uint32_t(e.arg));
    if (e.kind == EventKind::Sensor) releaseSlot(sensorReadings_, freeSensorReading_, std::uint32_t(e.arg));
    if (e.kind == EventKind::Timer && e.face == kTimerHasSlot) {
      TimerSlot& t = timers_[std::uint32_t(e.arg)];
      const std::uint32_t gen = std::uint32_t(e.arg >> 32);
      if (t.generation == gen || t.generation == gen + 1) {
        t.generation = gen + 1;
        releaseTimer(std::uint32_t(e.arg));
      }
    }
    return;
  }
  vs_event ev;
  ev.face = -1;
  ev.other = VS_NO_BLOCK;
  ev.data = nullptr;
  ev.size = 0;
  ev.timer_id = 0;
  ev.tag = 0;
  ev.sensor = 0;
  switch (e.kind) {
    case EventKind::Message: {
      MessageSlot& m = messages_[std::uint32_t(e.arg)];
      FaceState& sent = face(m.from, m.fromFace);
      if (sent.epoch != m.epoch) {
        // The link broke while this message was in flight; it was counted as dropped then.
        releaseMessage(std::uint32_t(e.arg));
        return;
      }
      --messagesInFlight_;
      if (--sent.inFlight == 0) facesInFlight_[m.from] &= std::uint16_t(~(1u << m.fromFace));
      ev.kind = VS_EV_MESSAGE;
      ev.face = e.face;
      ev.other = m.from;
      ev.data = m.data.data();
      ev.size = m.size;
      ++stats_.messagesReceived;
      break;
    }
    case EventKind::Timer: {
      ev.kind = VS_EV_TIMER;
      if (e.face != kTimerHasSlot) {
        ev.tag = e.arg;
        break;
      }
      const std::uint32_t slot = std::uint32_t(e.arg);
      TimerSlot& t = timers_[slot];
      const std::uint32_t gen = std::uint32_t(e.arg >> 32);
      if (t.generation == gen + 1) {  // cancelled: the slot was kept until now so the id stayed unique
        releaseTimer(slot);
        return;
      }
      if (t.generation != gen) return;
      t.generation = gen + 1;
      ev.kind = VS_EV_TIMER;
      ev.timer_id = e.arg;
      ev.tag = t.tag;
      releaseTimer(slot);
      break;
    }
    case EventKind::Start:
      break;
    case EventKind::NeighborAdded:
    case EventKind::NeighborRemoved:
      ev.kind = e.kind == EventKind::NeighborAdded ? VS_EV_NEIGHBOR_ADDED : VS_EV_NEIGHBOR_REMOVED;
      ev.face = e.face;
      ev.other = BlockId(e.arg);
      break;
    case EventKind::Tap:
      ev.kind = VS_EV_TAP;
      break;
    case EventKind::MotionEnd: {
      MotionSlot& m = motions_[std::uint32_t(e.arg)];
      clearMotionCells(m, world_.block(e.block).cell);
      world_.settle(world_.block(e.block).cell, e.block);
      world_.block(e.block).motion = kNoBlock;
      releaseMotion(std::uint32_t(e.arg));
      ++stats_.motionsEnded;
      formLinks(e.block);
      ev.kind = VS_EV_MOTION_END;
      break;
    }
    case EventKind::Sensor: {
      const std::array<std::int32_t, 3> v = sensorReadings_[std::uint32_t(e.arg)].values;
      releaseSlot(sensorReadings_, freeSensorReading_, std::uint32_t(e.arg));
      if (!accel_.empty()) accel_[e.block] = v;
      ev.kind = VS_EV_SENSOR;
      ev.sensor = VS_SENSOR_ACCEL;
      ev.values[0] = v[0];
      ev.values[1] = v[1];
      ev.values[2] = v[2];
      break;
    }
    case EventKind::Mobile:
      if (code_ && code_->abi_version < 3) return;  // (a program of ABI 2 knows no such event)
      ev.kind = VS_EV_MOBILE;
      ev.values[0] = std::int32_t(e.arg);
      ev.values[1] = e.face;
      ev.values[2] = 0;
      break;
    case EventKind::PhysicsStep:
      return dispatchPhysicsStep(e);
    case EventKind::Count:
      return;
  }
  ++stats_.eventsProcessed;
  ++stats_.eventsByKind[std::size_t(e.kind)];
  fingerprint_.add(e.time, e.block, e.kind);
  if (!eventObservers_.empty())
    for (SimulationObserver* o : eventObservers_) o->onEvent(*this, e);
  if (e.kind == EventKind::Start) {
    if (code_ && code_->start) {
      vs_ctx ctx{&kHostApi, this, e.block, blockState(e.block), code_->user};
      code_->start(&ctx);
    }
  } else {
    deliver(e.block, ev);
  }
  if (e.kind == EventKind::Message) releaseMessage(std::uint32_t(e.arg));
}

void Simulation::breakLinks(BlockId id) {
  for (int f = 0; f < faceCount_; ++f) {
    const BlockId n = world_.neighbor(id, f);
    if (n == kNoBlock) continue;
    const int back = world_.lattice().oppositeFace(world_.block(id).cell, f);
    const BlockId senders[2] = {id, n};
    const BlockId receivers[2] = {n, id};
    const int senderFaces[2] = {f, back};
    // With no message in flight anywhere there is nothing to drop: skip the per-face bookkeeping.
    for (int s = 0; s < 2 && messagesInFlight_ > 0; ++s) {
      // A face with nothing in flight has nothing to drop, and its transmitter is idle: its state
      // (usually a cache miss for the neighbor) need not be touched.
      std::uint16_t& mask = facesInFlight_[senders[s]];
      if (!(mask & (1u << senderFaces[s]))) continue;
      mask &= std::uint16_t(~(1u << senderFaces[s]));
      FaceState& fs = face(senders[s], senderFaces[s]);
      stats_.messagesDropped += fs.inFlight;
      messagesInFlight_ -= fs.inFlight;
      if (!observers_.empty())
        for (std::uint16_t k = 0; k < fs.inFlight; ++k)
          for (SimulationObserver* o : observers_)
            o->onMessageDropped(*this, senders[s], senderFaces[s], receivers[s]);
      fs.inFlight = 0;
      ++fs.epoch;
      fs.setBusyUntil(queue_.now());
    }
    world_.prefetchAlive(n);  // its notification is dispatched right after this event
    schedule(queue_.now(), id, EventKind::NeighborRemoved, f, n);
    schedule(queue_.now(), n, EventKind::NeighborRemoved, back, id);
  }
}

void Simulation::formLinks(BlockId id) {
  for (int f = 0; f < faceCount_; ++f) {
    const BlockId n = world_.neighbor(id, f);
    if (n == kNoBlock) continue;
    const int back = world_.lattice().oppositeFace(world_.block(id).cell, f);
    world_.prefetchAlive(n);  // its notification is dispatched right after this event
    schedule(queue_.now(), id, EventKind::NeighborAdded, f, n);
    schedule(queue_.now(), n, EventKind::NeighborAdded, back, id);
  }
}

BlockId Simulation::addBlockWhileRunning(const Cell& cell, std::uint32_t color) {
  if (!started_) return addBlock(cell, color);
  if (!world_.isFree(cell)) return kNoBlock;
  const BlockId id = world_.addBlock(cell, color);
  if (id == kNoBlock) return id;
  world_.block(id).rng = BlockRng::initialState(config_.seed, id);
  faceGroup_.push_back(kNoBlock);
  facesInFlight_.push_back(0);
  if (link_.jitter > 0) lastArrival_.resize(lastArrival_.size() + std::size_t(faceCount_), 0);
  if (target_.hasAccelerometer) accel_.push_back({0, 0, -1});
  if (target_.hasDisplayValue) displayValues_.push_back(0);
  if (stateSize_) {
    // The states move (block programs get their state's address per callback, never keep it).
    const std::size_t used = std::size_t(id) * stateSize_;
    std::vector<unsigned char, support::LargeAllocator<unsigned char>> grown(used + stateSize_ + 16, 0);
    unsigned char* raw = grown.data();
    unsigned char* base = raw + ((16 - (reinterpret_cast<std::uintptr_t>(raw) & 15)) & 15);
    std::memcpy(base, stateBase_, used);
    stateStorage_.swap(grown);
    stateBase_ = base;
  }
  schedule(queue_.now(), id, EventKind::Start, 0, 0);
  // Its neighbours learn of it; the block itself sees them at its start.
  for (int f = 0; f < faceCount_; ++f) {
    const BlockId n = world_.neighbor(id, f);
    if (n != kNoBlock)
      schedule(queue_.now(), n, EventKind::NeighborAdded, world_.lattice().oppositeFace(cell, f), id);
  }
  return id;
}

void Simulation::removeBlock(BlockId id) {
  startIfNeeded();
  Block& b = world_.block(id);
  if (!world_.isAlive(id)) return;
  if (b.motion != kNoBlock) {
    const MotionSlot& m = motions_[b.motion];  // released when its MotionEnd event comes
    clearMotionCells(m, b.cell);
    world_.clearCell(b.cell);
  } else {
    breakLinks(id);
    world_.clearCell(b.cell);
  }
  world_.markRemoved(id);
}

}  // namespace simcore
