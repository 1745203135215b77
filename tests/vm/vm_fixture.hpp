// Shared set-up of the VM store tests: a type table, predicates, a heap and a database built from
// them, plus short helpers to build argument arrays and to read a node's facts as strings.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "meldvm/database.hpp"
#include "meldvm/dump.hpp"
#include "meldvm/heap.hpp"
#include "meldvm/predicate.hpp"
#include "meldvm/types.hpp"

namespace vmtest {

using namespace meldvm;

inline Value I(std::int32_t i) { return Value::fromInt(i); }
inline Value F(double d) { return Value::fromFloat(d); }
inline Value N(NodeId n) { return Value::fromNode(n); }

struct Store {
  TypeTable types;
  PredicateTable preds{types};
  Heap heap{types};
  std::unique_ptr<Database> db;

  PredId linear(const std::string& name, std::vector<TypeId> fields) {
    PredicateDesc d;
    d.name = name;
    d.fields = std::move(fields);
    d.linear = true;
    return preds.add(std::move(d));
  }
  PredId persistent(const std::string& name, std::vector<TypeId> fields, bool compact = false) {
    PredicateDesc d;
    d.name = name;
    d.fields = std::move(fields);
    d.compact = compact;
    return preds.add(std::move(d));
  }
  PredId aggregate(const std::string& name, std::vector<TypeId> fields, AggregateKind k,
                   std::uint32_t field) {
    PredicateDesc d;
    d.name = name;
    d.fields = std::move(fields);
    d.aggregate = k;
    d.aggregateField = field;
    return preds.add(std::move(d));
  }
  // Builds the database once every predicate is declared.
  Database& open(NodeId nodes) {
    db = std::make_unique<Database>(preds, heap);
    db->addNodes(nodes);
    return *db;
  }
  ~Store() { db.reset(); }  // the database releases its values before the heap goes

  // The facts of one predicate at one node, in store order, printed as in the dump (one per slot,
  // with "xK" appended when the fact has K > 1 copies).
  std::vector<std::string> facts(NodeId n, PredId p) const {
    std::vector<std::string> out;
    for (FactRef f = db->first(n, p); f != kNoFact; f = db->next(p, f)) {
      std::string s;
      appendFact(s, *db, p, db->args(p, f));
      if (db->copies(p, f) > 1) s += " x" + std::to_string(db->copies(p, f));
      out.push_back(s);
    }
    return out;
  }
};

inline std::vector<std::string> S(std::initializer_list<const char*> l) { return {l.begin(), l.end()}; }

}  // namespace vmtest
