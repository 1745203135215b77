// An event of the discrete-event kernel: a small plain record, copied by value, never allocated.
#pragma once

#include <cstdint>

#include "simcore/time.hpp"

namespace simcore {

enum class EventKind : std::uint8_t {
  Start,            // block program start (time 0)
  Message,          // a message arrives at `block` on `face`; arg = message slot
  NeighborAdded,    // arg = neighbor id
  NeighborRemoved,  // arg = neighbor id
  Tap,              // user tap
  Timer,            // arg = timer id
  MotionEnd,        // arg = motion slot
  Sensor,           // arg = packed sensor reading slot
  Mobile,           // a mobile came over the block (face 1) or left it (face 0); arg = the mobile
  PhysicsStep,      // one step of the physics (simcore/physics.hpp); block 0, not delivered
  Count
};

const char* eventKindName(EventKind kind);

// Ties at equal time are broken by priority class, then insertion sequence: the order is total and
// independent of the future-event set implementation. World changes (motion ends) come before the
// topology notifications they cause, which come before messages and block-program events.
enum class PriorityClass : std::uint8_t { World = 0, Topology = 1, Message = 2, Program = 3 };
inline constexpr int kPriorityClassCount = 4;

// Inline: it is asked for every scheduled event.
inline PriorityClass priorityClassOf(EventKind kind) {
  switch (kind) {
    // Start is in the first class so that at t = 0 every block starts before anything that other
    // blocks' start callbacks (or scheduleTap/removeBlock before the run) cause at the same time:
    // the block ABI promises `start` before any `event`.
    case EventKind::Start:
    case EventKind::MotionEnd:
    case EventKind::PhysicsStep:
      return PriorityClass::World;
    case EventKind::NeighborAdded:
    case EventKind::NeighborRemoved:
      return PriorityClass::Topology;
    case EventKind::Message:
      return PriorityClass::Message;
    default:
      return PriorityClass::Program;
  }
}

struct Event {
  SimTime time = 0;
  std::uint64_t order = 0;  // (class << 56) | sequence: the tie-break key after time
  std::uint32_t block = 0;
  EventKind kind = EventKind::Start;
  std::uint8_t face = 0;
  std::uint16_t spare = 0;
  std::uint64_t arg = 0;

  static constexpr int kSequenceBits = 56;
  PriorityClass priorityClass() const { return PriorityClass(order >> kSequenceBits); }
  std::uint64_t sequence() const { return order & ((std::uint64_t(1) << kSequenceBits) - 1); }
};
static_assert(sizeof(Event) == 32, "events must stay small plain records");

inline bool earlier(const Event& a, const Event& b) {
  return a.time < b.time || (a.time == b.time && a.order < b.order);
}

}  // namespace simcore
