#include "simcore/event.hpp"

namespace simcore {

const char* eventKindName(EventKind kind) {
  switch (kind) {
    case EventKind::Start:
      return "start";
    case EventKind::Message:
      return "message";
    case EventKind::NeighborAdded:
      return "neighbor-added";
    case EventKind::NeighborRemoved:
      return "neighbor-removed";
    case EventKind::Tap:
      return "tap";
    case EventKind::Timer:
      return "timer";
    case EventKind::MotionEnd:
      return "motion-end";
    case EventKind::Sensor:
      return "sensor";
    case EventKind::Count:
      break;
  }
  return "?";
}

PriorityClass priorityClassOf(EventKind kind) {
  switch (kind) {
    // Start is in the first class so that at t = 0 every block starts before anything that other
    // blocks' start callbacks (or scheduleTap/removeBlock before the run) cause at the same time:
    // the block ABI promises `start` before any `event`.
    case EventKind::Start:
    case EventKind::MotionEnd:
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

}  // namespace simcore
