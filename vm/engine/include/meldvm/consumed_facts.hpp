// The facts a rule run consumed: marked when a rule fires, unlinked when the run ends
// (Machine::finishRuleRun). A NativeArray whose state is native_abi.h's meld_native_consumed, so
// that native code appends to it without a call (and calls the VM when it is full).
#pragma once

#include <cstddef>
#include <cstdint>

#include "meldvm/fact_table.hpp"
#include "meldvm/native_abi.h"
#include "meldvm/native_array.hpp"
#include "meldvm/predicate.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

class ConsumedFacts {
 public:
  struct Fact {
    NodeId node;
    PredId pred;
    FactRef fact;
  };
  static_assert(sizeof(Fact) == 12 && sizeof(NodeId) == 4 && sizeof(PredId) == 4 && sizeof(FactRef) == 4,
                "native code appends three 32-bit words per fact");

  void push(NodeId n, PredId p, FactRef f) { facts_.push_back({n, p, f}); }
  std::size_t size() const { return facts_.size(); }
  const Fact& operator[](std::size_t i) const { return facts_[i]; }
  void clear() { facts_.clear(); }
  std::size_t bytesReserved() const { return facts_.bytesReserved(); }
  meld_native_consumed* forNativeCode() {
    using State = NativeArray<Fact>::State;
    static_assert(sizeof(State) == sizeof(meld_native_consumed) &&
                  offsetof(State, size) == offsetof(meld_native_consumed, size) &&
                  offsetof(State, capacity) == offsetof(meld_native_consumed, capacity));
    return reinterpret_cast<meld_native_consumed*>(facts_.forNativeCode());
  }

 private:
  NativeArray<Fact> facts_;
};

}  // namespace meldvm
