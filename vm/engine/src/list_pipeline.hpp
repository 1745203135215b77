// The lists a loop fetches for the facts ahead of its visits, carried from one visit to the next
// (detail::listsStayPut). At each visit the fact k facts on (k = 1 .. K, kListPipelineAhead) has
// its cell at depth K - k on the way: the cell one visit before fetched for that fact, one cell
// deeper, so a visit reads one cell per fact ahead, where walking every list again from its first
// cell (Interpreter::fetchListsAhead) read K (K - 1) / 2 of them.
#pragma once

#include "meldvm/bytecode_internal.hpp"
#include "meldvm/fact_table.hpp"
#include "meldvm/heap.hpp"

namespace meldvm {

class ListPipeline {
 public:
  static constexpr int kAhead = detail::kListPipelineAhead;

  // Before visiting `fact` (the loop's first fact, then the next one at every call).
  void step(const FactTable& table, FactRef fact, std::uint32_t listField) {
    if (!started_) return start(table, fact, listField);
    for (int k = 1; k < kAhead; ++k) {  // the fact k + 1 on is now k on: one cell deeper
      const ConsCell* c = cells_[k];
      cells_[k - 1] = c ? c->tail : nullptr;
      __builtin_prefetch(cells_[k - 1]);  // (a prefetch of address 0 is harmless)
    }
    if (ahead_ != kNoFact) ahead_ = table.next(ahead_);
    cells_[kAhead - 1] = listOf(table, ahead_, listField);
    __builtin_prefetch(cells_[kAhead - 1]);
  }
  // The cell on the way for the fact k on (1 <= k <= kAhead), or null (for tests).
  const ConsCell* cellAhead(int k) const { return cells_[k - 1]; }

 private:
  static const ConsCell* listOf(const FactTable& table, FactRef f, std::uint32_t field) {
    return f == kNoFact ? nullptr : static_cast<const ConsCell*>(table.args(f)[field].asObject());
  }
  void start(const FactTable& table, FactRef fact, std::uint32_t listField) {
    started_ = true;
    ahead_ = fact;
    for (int k = 1; k <= kAhead; ++k) {
      if (ahead_ != kNoFact) ahead_ = table.next(ahead_);
      const ConsCell* cell = listOf(table, ahead_, listField);
      for (int d = kAhead - k; d > 0 && cell; --d) cell = cell->tail;
      cells_[k - 1] = cell;
      __builtin_prefetch(cell);
    }
  }

  bool started_ = false;
  FactRef ahead_ = kNoFact;        // the fact kAhead on
  const ConsCell* cells_[kAhead];  // [k - 1]: the cell of the fact k on
};

}  // namespace meldvm
