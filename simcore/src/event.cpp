#include "simcore/event.hpp"

namespace simcore {

const char* eventKindName(EventKind kind) {
  switch (kind) {
    case EventKind::Start: return "start";
    case EventKind::Message: return "message";
    case EventKind::NeighborAdded: return "neighbor-added";
    case EventKind::NeighborRemoved: return "neighbor-removed";
    case EventKind::Tap: return "tap";
    case EventKind::Timer: return "timer";
    case EventKind::MotionEnd: return "motion-end";
    case EventKind::Sensor: return "sensor";
    case EventKind::Count: break;
  }
  return "?";
}

PriorityClass priorityClassOf(EventKind kind) {
  switch (kind) {
    case EventKind::MotionEnd: return PriorityClass::World;
    case EventKind::NeighborAdded:
    case EventKind::NeighborRemoved: return PriorityClass::Topology;
    case EventKind::Message: return PriorityClass::Message;
    default: return PriorityClass::Program;
  }
}

}  // namespace simcore
