#include "meldvm/dump.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

#include "meldvm/value_ops.hpp"

namespace meldvm {

void appendFact(std::string& out, const Database& db, PredId p, const Value* args) {
  const PredicateDesc& d = db.predicates()[p];
  if (d.persistent()) out += '!';
  out += d.name;
  out += '(';
  for (std::uint32_t i = 0; i < d.arity(); ++i) {
    if (i) out += ", ";
    appendValue(out, db.types(), d.fields[i], args[i]);
  }
  out += ')';
}

// By name only (the "!" prefix plays no part), byte-wise like std::string's operator<.
std::vector<PredId> dumpOrder(const PredicateTable& preds) {
  std::vector<PredId> order(preds.size());
  std::iota(order.begin(), order.end(), PredId(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](PredId a, PredId b) { return preds[a].name < preds[b].name; });
  return order;
}

namespace {

// The sorted lines of p's facts on node n.
void collectLines(const Database& db, NodeId n, PredId p, std::vector<std::string>& lines) {
  const PredicateTable& preds = db.predicates();
  lines.clear();
  for (FactRef f = db.first(n, p); f != kNoFact; f = db.next(p, f)) {
    std::string line;
    appendFact(line, db, p, db.args(p, f));
    // Aggregated predicates show each current value once; other persistent facts per copy.
    const std::uint32_t copies = preds[p].aggregated() ? 1 : db.copies(p, f);
    for (std::uint32_t c = 1; c < copies; ++c) lines.push_back(line);
    lines.push_back(std::move(line));
  }
  std::sort(lines.begin(), lines.end());
}

}  // namespace

std::vector<PredicateFacts> nodeFacts(const Database& db, NodeId n) {
  std::vector<PredicateFacts> result;
  if (n >= db.nodeCount() || !db.alive(n)) return result;
  const PredicateTable& preds = db.predicates();
  for (PredId p : dumpOrder(preds)) {
    if (preds[p].action) continue;
    PredicateFacts group{p, {}};
    collectLines(db, n, p, group.lines);
    if (!group.lines.empty()) result.push_back(std::move(group));
  }
  return result;
}

void appendNodeDump(std::string& out, const Database& db, NodeId n, const std::vector<PredId>& order) {
  const PredicateTable& preds = db.predicates();
  std::vector<std::string> lines;
  out += std::to_string(n);
  out += '\n';
  for (PredId p : order) {
    if (preds[p].action) continue;
    collectLines(db, n, p, lines);
    for (const std::string& l : lines) {
      out += l;
      out += '\n';
    }
  }
}

void dumpDatabase(std::string& out, const Database& db) {
  const std::vector<PredId> order = dumpOrder(db.predicates());
  for (NodeId n = 0; n < db.nodeCount(); ++n)
    if (db.alive(n)) appendNodeDump(out, db, n, order);  // not the created nodes deleted by the GC (§6.10)
}

std::string dumpDatabase(const Database& db) {
  std::string out;
  dumpDatabase(out, db);
  return out;
}

void dumpDatabase(std::ostream& os, const Database& db) { os << dumpDatabase(db); }

}  // namespace meldvm
