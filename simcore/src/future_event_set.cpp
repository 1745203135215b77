#include "simcore/future_event_set.hpp"

#include "simcore/calendar_fes.hpp"
#include "simcore/heap_fes.hpp"

namespace simcore {

std::optional<FesKind> parseFesKind(std::string_view name) {
  if (name == "heap") return FesKind::Heap;
  if (name == "calendar") return FesKind::Calendar;
  return std::nullopt;
}

const char* fesKindName(FesKind kind) { return kind == FesKind::Heap ? "heap" : "calendar"; }

std::unique_ptr<FutureEventSet> makeFutureEventSet(FesKind kind) {
  if (kind == FesKind::Calendar) return std::make_unique<CalendarFes>();
  return std::make_unique<HeapFes>();
}

}  // namespace simcore
