// The future-event set: where pending events wait, ordered by (time, priority class, sequence).
// Implementations are interchangeable at run time and must give the same order.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string_view>

#include "simcore/event.hpp"

namespace simcore {

class FutureEventSet {
 public:
  virtual ~FutureEventSet() = default;
  virtual const char* name() const = 0;
  virtual void push(const Event& event) = 0;
  // The earliest event, or nullptr when empty. May reorganize internally, hence not const.
  virtual const Event* peek() = 0;
  // Removes the event last returned by peek(); peek() must have returned non-null just before.
  virtual void pop() = 0;
  // The k-th next event (k = 0 is peek()) when the implementation knows it cheaply, else nullptr.
  // Used only as a prefetch hint.
  virtual const Event* peekAhead(std::size_t /*k*/) { return nullptr; }
  virtual std::size_t size() const = 0;
  virtual void clear() = 0;
};

enum class FesKind { Heap, Calendar, Ladder };

// The queue vsim, brownian-flood and the IDE use unless told otherwise: the one that measured
// fastest on B1 (7k to 1M blocks: 1.4x to 3.4x the 4-ary heap) and B3 (Blinky Blocks and Catoms
// 3D, gradient and leader election: 1.2x to 1.6x), with the same results (bench/README.md).
inline constexpr FesKind kDefaultFes = FesKind::Ladder;

std::optional<FesKind> parseFesKind(std::string_view name);
const char* fesKindName(FesKind kind);
std::unique_ptr<FutureEventSet> makeFutureEventSet(FesKind kind);

}  // namespace simcore
