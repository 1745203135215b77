// The lists a loop fetches for the facts ahead of its visits, carried from one visit to the next
// (detail::listsStayPut). At each visit the fact k facts on (k = 1 .. kListPipelineFacts) has its
// cell at depth listPipelineDepth(k) on the way: the cell fetched for that fact before, one cell
// deeper every kListPipelineSpacing visits, so a visit reads at most one cell per fact ahead,
// where walking every list again from its first cell (walkListsAhead) read the cells above each
// fact's depth too: about D * D / 2 for lists fetched D cells deep.
#pragma once

#include <algorithm>

#include "meldvm/bytecode_internal.hpp"
#include "meldvm/fact_table.hpp"
#include "meldvm/heap.hpp"

namespace meldvm {

// For the facts k = 1 .. K on from `fact`: fetches the list cell at depth K - k of each one whose
// depth is at most maxDepth, and stores it in cells[k - 1] (null for none) when `cells` is given;
// returns the fact K on (kNoFact past the list's end). Walking the lists of 8queens-12
// (queens_violation) took a third of its run, waiting for one cell after another. The facts
// ahead are all alive: one consumed in this rule run keeps its arguments until the run ends
// (Machine::finishRuleRun), and an in-place update gives it new ones; so a loop whose lists may
// change walks this afresh at every visit (Interpreter::loop), and a ListPipeline walks it once.
// (Out of line: inlined in the loop, it cost n-queens 10 1 % more instructions.)
template <int K>
[[gnu::noinline]] FactRef walkListsAhead(const FactTable& table, FactRef fact, std::uint32_t listField,
                                         int maxDepth, const ConsCell** cells) {
  for (int k = 1; k <= K; ++k) {
    fact = table.next(fact);
    if (fact == kNoFact) {
      if (cells) std::fill(cells + k - 1, cells + K, nullptr);
      return kNoFact;
    }
    const ConsCell* cell = nullptr;
    if (K - k <= maxDepth) {
      cell = static_cast<const ConsCell*>(table.args(fact)[listField].asObject());
      for (int d = K - k; d > 0 && cell; --d) cell = cell->tail;
      __builtin_prefetch(cell);  // (a prefetch of address 0 is harmless)
    }
    if (cells) cells[k - 1] = cell;
  }
  return fact;
}

class ListPipeline {
 public:
  static constexpr int kAhead = detail::kListPipelineFacts;  // the facts whose cells are on the way

  // The depth of the cell on the way for the fact k on: one level deeper every
  // kListPipelineSpacing visits, so that each cell has that many visits to arrive.
  static constexpr int depthAhead(int k) { return detail::listPipelineDepth(k); }

  // Before visiting `fact` (the loop's first fact, then the next one at every call).
  void step(const FactTable& table, FactRef fact, std::uint32_t listField) {
    if (!started_) return start(table, fact, listField);
    for (int k = 1; k < kAhead; ++k) {  // the fact k + 1 on is now k on
      const ConsCell* c = cells_[k];
      if (depthAhead(k) != depthAhead(k + 1)) {  // one cell deeper
        c = c ? c->tail : nullptr;
        __builtin_prefetch(c);  // (a prefetch of address 0 is harmless)
      }
      cells_[k - 1] = c;
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
      for (int d = depthAhead(k); d > 0 && cell; --d) cell = cell->tail;
      __builtin_prefetch(cell);
      cells_[k - 1] = cell;
    }
  }

  bool started_ = false;
  FactRef ahead_ = kNoFact;        // the fact kAhead on
  const ConsCell* cells_[kAhead];  // [k - 1]: the cell of the fact k on
};

}  // namespace meldvm
