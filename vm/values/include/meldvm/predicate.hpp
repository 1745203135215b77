// Predicate descriptors (spec §4.1, §9.3): what the store and the dump need to know about a
// predicate. Arities and field indices exclude the home argument, as everywhere in the VM.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "meldvm/types.hpp"

namespace meldvm {

using PredId = std::uint32_t;

// Aggregate field kinds of type declarations (§4.1.2). `count` exists only as an aggregate
// *construct* in rule heads (§5.3.4), never on a declared field, so it is not a kind here.
enum class AggregateKind : std::uint8_t { None, First, Min, Max, Sum };

struct PredicateDesc {
  std::string name;            // as declared: printed in dumps with this spelling
  std::vector<TypeId> fields;  // home argument excluded
  bool linear = false;         // otherwise persistent (multiset with counts)
  bool route = false;          // §4.1.1
  bool reverseRoute = false;   // generated ___xxx inverse route (§6.7)
  bool action = false;         // executed, never stored
  bool thread = false;         // home is a thread node (§6.12)
  bool compact = false;        // persistent without de-duplication: every derivation appends
  AggregateKind aggregate = AggregateKind::None;
  std::uint32_t aggregateField = 0;  // valid when aggregate != None

  bool persistent() const { return !linear; }
  bool aggregated() const { return aggregate != AggregateKind::None; }
  std::uint32_t arity() const { return std::uint32_t(fields.size()); }
};

class PredicateTable {
 public:
  explicit PredicateTable(const TypeTable& types) : types_(types) {}

  // Checks the descriptor (types exist; an aggregate is on a persistent, non-compact predicate and a
  // field of an allowed type; names are unique ignoring case, §1.3) and returns its id.
  PredId add(PredicateDesc desc);

  const PredicateDesc& operator[](PredId p) const { return preds_[p]; }
  std::size_t size() const { return preds_.size(); }
  // Case-insensitive look-up (§1.3); returns size() when absent.
  PredId find(std::string_view name) const;
  const TypeTable& types() const { return types_; }

 private:
  const TypeTable& types_;
  std::vector<PredicateDesc> preds_;
};

}  // namespace meldvm
