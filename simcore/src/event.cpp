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
    case EventKind::Mobile:
      return "mobile";
    case EventKind::PhysicsStep:
      return "physics-step";
    case EventKind::Sensor:
      return "sensor";
    case EventKind::Count:
      break;
  }
  return "?";
}

}  // namespace simcore
