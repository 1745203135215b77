#include "meldvm/node_directory.hpp"

#include <string>

#include "meldvm/arith.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldvm::threads {

namespace {

// Cuts [0, graph) into `threads` contiguous ranges of about equal weight. Why weights: a node's
// work grows with the facts it starts with (its edges, mostly), and graphs list their busy nodes
// unevenly: pagerank-movies' first half holds 72 % of its edges, so equal counts of nodes left
// one thread with most of the work until a rebalance moved nodes over (a fifth of a 50 ms run).
std::vector<NodeId> weightedCuts(const Program& program, NodeId graph, ThreadId threads) {
  // Two passes over the axioms rather than an array of weights: graphs run to millions of nodes.
  auto weight = [&](NodeId n) {
    std::uint64_t w = 1;
    if (n < program.nodeAxioms.size())
      if (const std::uint32_t b = program.nodeAxioms[n]; b != Program::kNoAxioms)
        detail::forEachAxiomStore(program, program.axiomCode(b),
                                  [&](PredId, std::size_t count) { w += count; });
    return w;
  };
  std::uint64_t total = 0;
  for (NodeId n = 0; n < graph; ++n) total += weight(n);
  std::vector<NodeId> cuts(threads + 1, graph);
  cuts[0] = 0;
  std::uint64_t before = 0;  // the weight of the nodes below n
  NodeId n = 0;
  std::uint64_t w = graph ? weight(0) : 0;  // node n's
  for (ThreadId t = 1; t < threads; ++t) {
    const std::uint64_t goal = total * t / threads;
    auto step = [&] {
      before += w;
      if (++n < graph) w = weight(n);
    };
    while (n < graph && before + w <= goal) step();
    // The node that straddles the goal goes below the cut if its end is nearer the goal.
    if (n < graph && before < goal && goal - before > before + w - goal) step();
    cuts[t] = n;
  }
  return cuts;
}

}  // namespace

NodeDirectory::NodeDirectory(const Program& program, NodeId graphNodes, ThreadId threads, bool threadNodes)
    : graph_(graphNodes),
      threads_(threads),
      cuts_(weightedCuts(program, graphNodes, threads)),
      createdBase_(graphNodes + (threadNodes ? threads : 0)),
      owners_(graphNodes, threads),
      blockOwner_(new std::atomic<ThreadId>[kMaxBlocks]) {
  for (ThreadId t = 1; t < threads; ++t)  // (thread 0's are the zeros it starts with)
    owners_.assignInitial(firstOwned(t), endOwned(t), t);
  for (std::uint32_t b = 0; b < kMaxBlocks; ++b) blockOwner_[b].store(kNoThread, std::memory_order_relaxed);
}

NodeId NodeDirectory::allocateBlock(ThreadId t, NodeId& count) {
  const std::uint32_t block = blocks_.fetch_add(1, std::memory_order_relaxed);
  const std::uint64_t first = std::uint64_t(createdBase_) + std::uint64_t(block) * kBlockIds;
  if (block >= kMaxBlocks || first + kBlockIds > 0xFFFFFFF0ull)
    throw RuntimeError("exists: no node ids left (" + std::to_string(kMaxBlocks) + " blocks of " +
                       std::to_string(kBlockIds) + " created nodes)");
  blockOwner_[block].store(t, std::memory_order_release);
  count = kBlockIds;
  return NodeId(first);
}

NodeId NodeDirectory::idEnd() const {
  const std::uint64_t blocks = std::min<std::uint32_t>(blocks_.load(std::memory_order_acquire), kMaxBlocks);
  return NodeId(createdBase_ + blocks * kBlockIds);
}

}  // namespace meldvm::threads
