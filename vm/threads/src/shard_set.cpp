#include "meldvm/shard_set.hpp"

#include "meldvm/dump.hpp"

namespace meldvm {

std::string dumpShards(const Program& program, const threads::NodeDirectory& directory,
                       const std::vector<const Machine*>& shards) {
  std::string out;
  const std::vector<PredId> order = dumpOrder(program.predicates);
  const NodeId end = directory.idEnd();
  for (NodeId n = 0; n < end; ++n) {
    const ThreadId t = directory.ownerOf(n);
    if (t == kNoThread) continue;
    const Machine& m = *shards[t];
    if (m.holdsNode(n)) appendNodeDump(out, m.database(), n, order);
  }
  return out;
}

void collectGarbageNodes(const std::vector<Machine*>& shards) {
  std::vector<std::uint8_t> referenced;
  bool anyEmpty = false;
  for (Machine* m : shards) anyEmpty = anyEmpty || !m->emptyCreatedNodes().empty();
  if (!anyEmpty) return;
  for (Machine* m : shards) m->markReferencedNodes(referenced);
  for (Machine* m : shards)
    for (NodeId n : m->emptyCreatedNodes())
      if (n >= referenced.size() || !referenced[n]) m->removeNode(n);
}

MachineStats sumStats(const std::vector<const Machine*>& shards) {
  MachineStats all;
  for (const Machine* m : shards) {
    const MachineStats& s = m->stats();
    all.factsDerived += s.factsDerived;
    all.factsTried += s.factsTried;
    all.factsConsumed += s.factsConsumed;
    all.factsSent += s.factsSent;
    all.rulesFired += s.rulesFired;
    all.nodeRuns += s.nodeRuns;
  }
  return all;
}

}  // namespace meldvm
