// A Simulation owns everything of one run: the world, the event queue, the block program's state,
// the statistics and the fingerprint. No globals: tests build many in one process.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simcore/blockcode.h"
#include "simcore/event_queue.hpp"
#include "simcore/motion_rule.hpp"
#include "simcore/observer.hpp"
#include "simcore/physics.hpp"
#include "simcore/stats.hpp"
#include "simcore/target_spec.hpp"
#include "simcore/world.hpp"

namespace simcore {

struct SimulationConfig {
  std::uint64_t seed = 1;
  FesKind fes = kDefaultFes;
  // Overrides of the target's defaults (negative = keep the target's value).
  double linkRateBitsPerSecond = -1;
  SimTime linkLatency = -1;
  SimTime linkJitter = -1;
  SimTime motionDuration = -1;
};

enum class RunStatus { Idle, TimeLimit, EventLimit };

class Simulation {
 public:
  Simulation(const TargetSpec& target, GridSize size, const SimulationConfig& config = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // --- Building the world (before the first run call) ---
  BlockId addBlock(const Cell& cell, std::uint32_t color);
  BlockId addBlock(const Cell& cell) { return addBlock(cell, target_.defaultColor); }
  // The block program every block runs. The table must outlive the simulation.
  void setBlockCode(const vs_blockcode* code);
  // Both throw std::invalid_argument for an unknown block or a time before now().
  void scheduleTap(BlockId block, SimTime time);
  void scheduleAccel(BlockId block, SimTime time, std::int32_t x, std::int32_t y, std::int32_t z);

  // --- Running ---
  // Process events while the next one is at or before `until`, at most `maxEvents` of them.
  // Idle: queue empty (or the next event is after `until`: then now() is advanced to `until`).
  RunStatus run(SimTime until = kTimeInfinity, std::uint64_t maxEvents = UINT64_MAX);
  RunStatus runUntilEmpty() { return run(); }
  RunStatus runUntil(SimTime t) { return run(t); }
  // Process exactly one event; false if none is pending.
  bool step() { return run(kTimeInfinity, 1) == RunStatus::EventLimit; }

  // --- Changing the world while it runs (tests, IDE) ---
  // Removes a block: its links break (in-flight messages on them are dropped) and neighbors are told.
  void removeBlock(BlockId id);
  // Adds a block to the running world (before the start: addBlock): it gets the next id and a
  // Start event now; its neighbours are told (NeighborAdded now). kNoBlock if the cell is outside,
  // invalid or taken.
  BlockId addBlockWhileRunning(const Cell& cell, std::uint32_t color);

  // --- Observing ---
  SimTime now() const { return queue_.now(); }
  const World& world() const { return world_; }
  World& world() { return world_; }
  const TargetSpec& target() const { return target_; }
  const LinkModel& link() const { return link_; }
  const Statistics& statistics() const;
  std::uint64_t fingerprint() const { return fingerprint_.value(); }
  std::uint64_t seed() const { return config_.seed; }
  const char* fesName() const;
  std::size_t pendingEvents() const { return queue_.size(); }
  void addObserver(SimulationObserver* observer) {
    observers_.push_back(observer);
    if (observer->wantsEvents()) eventObservers_.push_back(observer);
    if (observer->wantsMessages()) messageObservers_.push_back(observer);
  }
  void removeObserver(SimulationObserver* observer);
  // Mobiles and air jets (Smart Blocks; before the start). Without, nothing of physics runs.
  void setPhysics(std::unique_ptr<Physics> physics);
  const Physics* physics() const { return physics_.get(); }
  // Asked before every legal motion starts (nullptr: none); not owned.
  void setMotionCheck(MotionCheck* check) { motionCheck_ = check; }
  // Interpolated position (cell units) of a block, mid-motion included.
  Vec3 position(BlockId id) const;
  // The value a block displays (targets with a display; 0 otherwise).
  std::int32_t displayValue(BlockId id) const { return displayValues_.empty() ? 0 : displayValues_[id]; }
  // The block program's per-block state (nullptr if none).
  void* blockState(BlockId id) { return stateSize_ ? stateBase_ + std::size_t(id) * stateSize_ : nullptr; }
  std::string blockInfo(BlockId id);

  // Host services behind the block ABI (blockcode.h). Public for the C trampolines only.
  struct Services;

 private:
  // 12 bytes with 4-byte alignment (the time is split) so a block's faces share a cache line.
  struct FaceState {
    std::uint32_t busyLow = 0, busyHigh = 0;  // end of the last transmission queued on this face
    std::uint16_t epoch = 0;                  // bumped whenever the link on this face breaks
    std::uint16_t inFlight = 0;               // messages sent on this face, not yet delivered
    SimTime busyUntil() const { return SimTime((std::uint64_t(busyHigh) << 32) | busyLow); }
    void setBusyUntil(SimTime t) {
      busyLow = std::uint32_t(std::uint64_t(t));
      busyHigh = std::uint32_t(std::uint64_t(t) >> 32);
    }
  };
  struct MessageSlot {
    BlockId from = kNoBlock;
    std::uint8_t fromFace = 0;
    std::uint16_t epoch = 0;
    std::uint32_t size = 0;
    std::uint32_t nextFree = kNoBlock;
    std::vector<std::uint8_t> data;  // capacity is kept across reuse
  };
  // The destination is the block's cell; the start is end - motionDuration_. The swept cells
  // (reserved for the whole motion) and the pivot (for position(); -1: none) are named by faces of
  // `from` and of the destination, as the target's MotionPlan said.
  struct MotionSlot {
    Cell from;
    std::uint32_t nextFree = kNoBlock;
    SimTime end = 0;
    std::uint16_t sweptFromFaces = 0, sweptToFaces = 0;
    std::int8_t pivotFace = -1;
  };
  static_assert(sizeof(MotionSlot) == 32);
  // Timer events carry their tag in `arg`, unless the program asked for an id to cancel them: then
  // `face` is kTimerHasSlot and `arg` is (generation << 32 | slot) of a TimerSlot.
  static constexpr std::uint8_t kTimerHasSlot = 1;
  struct TimerSlot {
    std::uint64_t tag = 0;
    std::uint32_t generation = 0;  // odd while the timer is pending
    std::uint32_t nextFree = kNoBlock;
    bool pending() const { return generation & 1u; }
  };

  void startIfNeeded();
  void checkExternalEvent(BlockId block, SimTime time, const char* what) const;
  void dispatch(const Event& e);
  void deliver(BlockId block, const vs_event& ev);
  void breakLinks(BlockId id);
  void formLinks(BlockId id);
  void schedule(SimTime t, BlockId b, EventKind k, int face, std::uint64_t arg, bool bypassFifo = false) {
    queue_.schedule(t, priorityClassOf(k), b, k, std::uint8_t(face), arg, bypassFifo);
  }
  void prefetchRecords(const Event& e) const;
  void prefetchCells(const Event& e) const;
  // A block's face states exist from its first send on (most blocks of a large world may never
  // send); faceGroup_[b] is the index of its group of faceCount_ states, or kNoBlock.
  FaceState& face(BlockId b, int f) {
    return faces_[std::size_t(faceGroup_[b]) * std::size_t(faceCount_) + std::size_t(f)];
  }
  FaceState& faceForSending(BlockId b, int f);
  SimTime transmissionTime(std::uint32_t size) const;
  void releaseMessage(std::uint32_t slot);
  void releaseMotion(std::uint32_t slot);
  // Physics: one step now; the next one scheduled unless one is; blocks told of coverage changes.
  void stepPhysics();
  void dispatchPhysicsStep(const Event& e);
  void wakePhysics();
  void announceCoverage();
  int mobileAbove(BlockId id, std::int32_t* mobile, double xyAngle[3]) const;
  int airJet(BlockId id, int face, double power, SimTime duration);
  // Frees the origin and the swept cells of a motion whose destination is `to` (not `to` itself).
  // (Translations, B1's motions, have no swept cells: the rest stays out of their way.)
  void clearMotionCells(const MotionSlot& m, const Cell& to) {
    world_.clearCell(m.from);
    if (m.sweptFromFaces | m.sweptToFaces) [[unlikely]] setSweptCells(m, to, kNoBlock);
  }
  // Reserves the swept cells of a motion for block `id`, or frees them (id = kNoBlock).
  [[gnu::noinline]] void setSweptCells(const MotionSlot& m, const Cell& to, BlockId id);
  void releaseTimer(std::uint32_t slot);

  // Services (called through the ABI).
  int send(BlockId from, int face, const void* data, std::uint32_t size, SimTime delay);
  int move(BlockId id, int face);
  int setTimer(BlockId id, SimTime delay, std::uint64_t tag, std::uint64_t* timerId);
  int cancelTimer(std::uint64_t timerId);
  void setColor(BlockId id, std::uint32_t rgb);

  TargetSpec target_;
  SimulationConfig config_;
  LinkModel link_;
  std::shared_ptr<const MotionRule> motionRule_;  // the target's own rule, if any
  bool translates_;                               // no rule of its own, but canTranslate
  MotionCheck* motionCheck_ = nullptr;
  std::unique_ptr<Physics> physics_;
  bool physicsScheduled_ = false;
  SimTime motionDuration_;
  World world_;
  int faceCount_;
  EventQueue queue_;
  std::vector<FaceState, support::LargeAllocator<FaceState>> faces_;
  std::vector<std::uint32_t> faceGroup_;
  std::uint64_t messagesInFlight_ = 0;        // sent, not yet delivered nor dropped
  std::vector<std::uint16_t> facesInFlight_;  // per block: bit f set while face f has messages in flight
  std::vector<MessageSlot> messages_;
  std::uint32_t freeMessage_ = kNoBlock;
  std::vector<MotionSlot, support::LargeAllocator<MotionSlot>> motions_;
  std::uint32_t freeMotion_ = kNoBlock;
  std::vector<TimerSlot, support::LargeAllocator<TimerSlot>> timers_;
  std::uint32_t freeTimer_ = kNoBlock;
  std::vector<std::int32_t> displayValues_;         // per block (targets with a display)
  std::vector<std::array<std::int32_t, 3>> accel_;  // latest reading per block (targets with one)
  struct SensorSlot {
    std::array<std::int32_t, 3> values{};
    std::uint32_t nextFree = kNoBlock;
  };
  std::vector<SensorSlot> sensorReadings_;  // readings of scheduled Sensor events
  std::uint32_t freeSensorReading_ = kNoBlock;
  std::uint64_t jitterRng_ = 0;
  std::vector<SimTime> lastArrival_;  // per face, only with jitter (keeps links in order)

  const vs_blockcode* code_ = nullptr;
  std::uint32_t stateSize_ = 0;
  std::vector<unsigned char, support::LargeAllocator<unsigned char>> stateStorage_;
  unsigned char* stateBase_ = nullptr;
  bool started_ = false;

  mutable Statistics stats_;
  Fingerprint fingerprint_;
  std::vector<SimulationObserver*> observers_;
  std::vector<SimulationObserver*> eventObservers_, messageObservers_;  // those of observers_ that want them
  double wallSeconds_ = 0;
};

}  // namespace simcore
