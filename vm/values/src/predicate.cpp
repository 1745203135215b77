#include "meldvm/predicate.hpp"

#include <cctype>
#include <stdexcept>

#include "support/text.hpp"

namespace meldvm {

namespace {

using support::sameIgnoringCase;

bool numeric(const TypeTable& types, TypeId t) {
  return types.kind(t) == TypeKind::Int || types.kind(t) == TypeKind::Float;
}

}  // namespace

PredId PredicateTable::find(std::string_view name) const {
  for (PredId p = 0; p < preds_.size(); ++p)
    if (sameIgnoringCase(preds_[p].name, name)) return p;
  return PredId(preds_.size());
}

PredId PredicateTable::add(PredicateDesc d) {
  const auto fail = [&](const std::string& why) {
    throw std::invalid_argument("meldvm: predicate '" + d.name + "': " + why);
  };
  if (d.name.empty()) fail("empty name");
  if (find(d.name) != preds_.size()) fail("declared twice");
  for (TypeId t : d.fields)
    if (t >= types_.size()) fail("unknown field type");
  if (d.linear && d.compact) fail("compact applies to persistent predicates only");
  if (d.aggregated()) {
    if (d.linear) fail("aggregate on a linear predicate");
    if (d.compact) fail("aggregate on a compact predicate");
    if (d.action) fail("aggregate on an action");
    if (d.aggregateField >= d.fields.size()) fail("aggregate field out of range");
    const TypeId t = d.fields[d.aggregateField];
    switch (d.aggregate) {
      case AggregateKind::Min:
      case AggregateKind::Max:
        if (!numeric(types_, t)) fail("min/max needs an int or float field");
        break;
      case AggregateKind::Sum:
        // `sum list int` passes cl-meld's checker but cannot be encoded (§4.1.2): refused here.
        if (!numeric(types_, t) &&
            !(types_.kind(t) == TypeKind::List && types_.kind(types_.element(t)) == TypeKind::Float))
          fail("sum needs an int, float or list float field");
        break;
      default:
        break;
    }
  }
  preds_.push_back(std::move(d));
  return PredId(preds_.size() - 1);
}

}  // namespace meldvm
