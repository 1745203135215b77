// One shard of a threaded run, for tests that drive a Machine by hand: a ShardLink that does
// nothing but say who owns a node and count the safe points, and programs whose rule 0 consumes
// `_init` and nothing else runs.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "bytecode_fixture.hpp"
#include "meldvm/machine.hpp"

namespace bctest {

// Node n belongs to owners[n] (thread 0 past the end); each safe point is counted and runs
// atSafePoint, if set; facts for other threads are only counted.
class TestShardLink final : public ShardLink {
 public:
  ThreadId ownerOf(NodeId n) const override { return n < owners.size() ? owners[n] : 0; }
  void sendRemote(ThreadId, NodeId, PredId, const Value*, bool) override { ++remoteSends; }
  void coordinateRemote(ThreadId, Opcode, NodeId, double) override {}
  NodeId allocateNodeBlock(ThreadId, NodeId& count) override {
    count = 0;
    return 0;
  }
  void requestMove(NodeId, ThreadId) override {}
  void stopAll() override {}
  void staticChanged(ThreadId, int) override {}
  std::int32_t staticNodes(ThreadId) const override { return 0; }
  void safePoint() override {
    ++safePoints;
    if (atSafePoint) atSafePoint();
  }
  std::vector<ThreadId> owners;
  int safePoints = 0;
  int remoteSends = 0;
  std::function<void()> atSafePoint;
};

// `nodes` nodes without axioms, each starting with `_init` (predicate 0), which rule 0 consumes;
// addPredicates declares the test's own predicates (1, 2, ...), which no rule reads.
inline std::unique_ptr<Program> initOnlyProgram(std::uint32_t nodes,
                                                const std::function<void(Program&)>& addPredicates = {}) {
  auto p = std::make_unique<Program>();
  p->initPredicate = pred(*p, "_init", {}, true);
  if (addPredicates) addPredicates(*p);
  emit(p->globalsInit, Opcode::RET);
  for (std::uint32_t n = 0; n < nodes; ++n) {
    p->nodeSourceIds.push_back(n);
    p->nodeAxioms.push_back(Program::kNoAxioms);
  }
  Rule r;
  r.block.slots = 1;
  r.bodyPredicates = {p->initPredicate};
  loop(r.block, Opcode::ITER, {p->initPredicate, 0, kLinConsume | kIterConsumableClass},
       [&] { emit(r.block, Opcode::FIRE, {0}); });
  emit(r.block, Opcode::RET);
  p->rules.push_back(std::move(r));
  verifyProgram(*p);
  return p;
}

}  // namespace bctest
