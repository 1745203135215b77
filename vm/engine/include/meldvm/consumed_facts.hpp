// The facts a rule run consumed: marked when a rule fires, unlinked when the run ends
// (Machine::finishRuleRun). A plain array whose state is native_abi.h's meld_native_consumed, so
// that native code appends to it without a call (and calls the VM when it is full).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meldvm/fact_table.hpp"
#include "meldvm/native_abi.h"
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

  ConsumedFacts() = default;
  ConsumedFacts(const ConsumedFacts&) = delete;  // native code holds the state's address
  ConsumedFacts& operator=(const ConsumedFacts&) = delete;

  void push(NodeId n, PredId p, FactRef f) {
    if (state_.size == state_.capacity) [[unlikely]]
      grow();
    facts()[state_.size++] = {n, p, f};
  }
  std::size_t size() const { return state_.size; }
  const Fact& operator[](std::size_t i) const { return facts()[i]; }
  void clear() { state_.size = 0; }
  std::size_t bytesReserved() const { return storage_.capacity() * sizeof(Fact); }
  meld_native_consumed* forNativeCode() { return &state_; }

 private:
  Fact* facts() const { return static_cast<Fact*>(state_.facts); }
  void grow() {  // as a std::vector grows (the memory a robot's VM reports stays the same)
    storage_.resize(std::max<std::size_t>(1, storage_.size() * 2));
    state_.facts = storage_.data();
    state_.capacity = std::uint32_t(storage_.size());
  }

  std::vector<Fact> storage_;
  meld_native_consumed state_{};
};

}  // namespace meldvm
