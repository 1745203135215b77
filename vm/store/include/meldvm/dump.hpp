// The database dump of spec §8 (the established VM's `meld -d`), byte for byte: for each live node
// in increasing id, its id on a line, then for each predicate in byte-wise name order one line per
// fact (a persistent fact once per copy), the lines of one predicate sorted byte-wise.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "meldvm/database.hpp"

namespace meldvm {

// One fact as printed: "!" for persistent predicates, the name, "(", the arguments without the
// home separated by ", ", ")". The home argument is not printed.
void appendFact(std::string& out, const Database& db, PredId p, const Value* args);

// The facts of one node exactly as its section of the dump lists them, grouped by predicate (in
// dump order; predicates without facts are left out); for inspectors that show one node.
struct PredicateFacts {
  PredId pred;
  std::vector<std::string> lines;
};
std::vector<PredicateFacts> nodeFacts(const Database& db, NodeId n);

void dumpDatabase(std::string& out, const Database& db);
// One node's section of the dump (its id, then its facts), for dumps merged from several stores
// (the threaded VM): `order` is dumpOrder's.
std::vector<PredId> dumpOrder(const PredicateTable& preds);
void appendNodeDump(std::string& out, const Database& db, NodeId n, const std::vector<PredId>& order);
std::string dumpDatabase(const Database& db);
void dumpDatabase(std::ostream& os, const Database& db);

}  // namespace meldvm
