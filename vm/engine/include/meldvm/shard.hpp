// One Machine as a shard of a threaded run (the multicore target, `meld -j N`, vm/threads): each
// worker thread owns a Machine with its own store, heap and scheduler, and the nodes of its part
// of the graph. What the Machine asks of the runtime around it is this interface; without it
// (MachineOptions::shard null) the Machine is the serial VM and none of this costs anything.
//
// Why shards rather than one shared store: the fact tables, their hash tables and the heap's
// reference counts are shared by all nodes of a store, so two threads writing one store would need
// a lock or an atomic on every fact. A shard touches only its own store; facts for another
// thread's nodes travel through per-pair channels, their boxed values handed over (heap.hpp,
// Heap::share).
#pragma once

#include <cstdint>

#include "meldvm/node_owners.hpp"
#include "meldvm/program.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

inline constexpr ThreadId kNoThread = 0xFFFFFFFFu;

// Where a shard sits in the run: its thread, the node range it owns at the start.
struct ShardPlacement {
  ThreadId self = 0;
  ThreadId threads = 1;
  NodeId firstOwned = 0, endOwned = 0;  // initial nodes [firstOwned, endOwned)
};

class ShardLink {
 public:
  virtual ~ShardLink() = default;
  // The thread that owns node n now (initial, thread and created nodes), or kNoThread when no
  // node n exists.
  virtual ThreadId ownerOf(NodeId n) const = 0;
  // The graph nodes' owners, read by the Machine on every fact it sends without a call (ownerOf
  // answers for the thread nodes and created ones); null: ownerOf answers for all.
  virtual const NodeOwners* graphOwners() const { return nullptr; }
  // A fact for node `dest` of thread `to`; the link takes over the references of its boxed
  // arguments. Sent in order: facts from one thread to one node arrive in sending order.
  virtual void sendRemote(ThreadId to, NodeId dest, PredId p, const Value* args, bool negative) = 0;
  // A coordination fact (§5.7: priorities, schedule-next, static/moving) for another thread's
  // node; `op` is the opcode, SET_PRIORITY for set-priority.
  virtual void coordinateRemote(ThreadId to, Opcode op, NodeId n, double value) = 0;
  // A block of fresh node ids for nodes this shard creates (exists): [first, first + count).
  virtual NodeId allocateNodeBlock(ThreadId self, NodeId& count) = 0;
  // set-cpu / set-affinity: node n (a node of the graph) moves to thread `to` at the next
  // rebalance, where it is pinned and gets its just-moved fact.
  virtual void requestMove(NodeId n, ThreadId to) = 0;
  // stop-program: every thread stops after its current node run.
  virtual void stopAll() = 0;
  // set-static / set-moving changed how many nodes of thread t are static (cpu-static, §5.7).
  virtual void staticChanged(ThreadId t, int delta) = 0;
  virtual std::int32_t staticNodes(ThreadId t) const = 0;
  // Between two rules of a node run, or while it takes in its facts, when
  // MachineOptions::safePointFlag is set: the runtime may deliver facts to this shard and move its
  // other nodes away (Machine::movableNow).
  virtual void safePoint() {}
};

}  // namespace meldvm
