#include "simcore/future_event_set.hpp"

#include "simcore/calendar_fes.hpp"
#include "simcore/heap_fes.hpp"
#include "simcore/ladder_fes.hpp"

namespace simcore {

std::optional<FesKind> parseFesKind(std::string_view name) {
  if (name == "heap") return FesKind::Heap;
  if (name == "calendar") return FesKind::Calendar;
  if (name == "ladder") return FesKind::Ladder;
  return std::nullopt;
}

const char* fesKindName(FesKind kind) {
  switch (kind) {
    case FesKind::Heap:
      return "heap";
    case FesKind::Calendar:
      return "calendar";
    case FesKind::Ladder:
      return "ladder";
  }
  return "?";
}

std::unique_ptr<FutureEventSet> makeFutureEventSet(FesKind kind) {
  if (kind == FesKind::Calendar) return std::make_unique<CalendarFes>();
  if (kind == FesKind::Ladder) return std::make_unique<LadderFes>();
  return std::make_unique<HeapFes>();
}

}  // namespace simcore
