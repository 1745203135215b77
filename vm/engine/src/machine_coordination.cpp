// The Machine's coordination facts (§5.7) and what the built-ins ask of the scheduler. In a
// threaded run (MachineOptions::shard) a coordination fact for another thread's node is sent to
// that thread, which applies it (coordinateOwned).
#include "meldvm/arith.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

namespace {
const Value kNoArgs[1] = {};  // arguments of just-moved (home only)

std::string nodeName(NodeId n) { return "@" + std::to_string(n); }
}  // namespace

void Machine::priorityRequest(NodeId n, double p) {
  if (!options_.coordination) return;
  if (n == running_ && inRun_) return;  // §5.7: ignored for the running node
  if (shard_ && !ownedHere(n)) [[unlikely]] {
    const ThreadId owner = ownerOf(n);
    if (owner == kNoThread)
      throw RuntimeError("set-priority for node " + nodeName(n) + ", which does not exist");
    if (owner != placement_.self) return shard_->coordinateRemote(owner, Opcode::SET_PRIORITY, n, p);
  }
  // One request per node: the most urgent (the established VM's COORDINATION_BUFFERING).
  const auto [it, added] = priorityRequests_.try_emplace(n, p);
  if (!added && sched_.moreUrgent(p, it->second)) it->second = p;
}

void Machine::applyPriorityRequests() {
  for (const auto& [n, p] : priorityRequests_) {
    if (shard_ && !ownedHere(NodeId(n))) [[unlikely]]  // it moved during the run (a safe point)
      shard_->coordinateRemote(ownerOf(NodeId(n)), Opcode::SET_PRIORITY, NodeId(n), p);
    else
      sched_.setPriority(NodeId(n), p);
  }
  priorityRequests_.clear();
}

void Machine::coordination(Opcode op, NodeId n, Value arg) {
  if (!options_.coordination && op != Opcode::SCHEDULE_NEXT) return;
  if (op == Opcode::SET_AFFINITY || op == Opcode::SET_CPU) return placeNode(op, n, arg);
  const double value = op == Opcode::ADD_PRIORITY || op == Opcode::SET_DEFAULT_PRIORITY ? arg.asFloat() : 0.0;
  if (shard_ && !ownedHere(n)) {
    const ThreadId owner = ownerOf(n);
    if (owner == kNoThread)
      throw RuntimeError("coordination fact for node " + nodeName(n) + ", which does not exist");
    if (owner != placement_.self) return shard_->coordinateRemote(owner, op, n, value);
  } else if (n >= db_->nodeCount()) {
    throw RuntimeError("coordination fact for node " + nodeName(n) + ", which does not exist");
  }
  if (op == Opcode::ADD_PRIORITY && n == running_ && inRun_) return;  // §5.7: not the running node
  // schedule-next of the running node only gives it the most urgent priority until its run ends:
  // it is not queued again (the established VM's do_set_node_priority for the current node).
  if (op == Opcode::SCHEDULE_NEXT && n == running_ && inRun_) return sched_.scheduleRunning(n);
  coordinateOwned(op, n, value);
}

void Machine::coordinateOwned(Opcode op, NodeId n, double value) {
  switch (op) {
    case Opcode::SET_PRIORITY:
      sched_.setPriority(n, value);
      break;
    case Opcode::ADD_PRIORITY:
      sched_.addPriority(n, value);
      break;
    case Opcode::REMOVE_PRIORITY:
      sched_.removePriority(n);
      break;
    case Opcode::SET_DEFAULT_PRIORITY:
      sched_.setDefaultPriority(n, value);
      break;
    case Opcode::SCHEDULE_NEXT:
      sched_.scheduleNext(n);
      break;
    case Opcode::SET_STATIC:
      setStatic(n, true);
      break;
    case Opcode::SET_MOVING:
      setStatic(n, false);
      break;
    default:
      break;
  }
}

void Machine::setStatic(NodeId n, bool isStatic) {
  if (sched_.isStatic(n) == isStatic) return;
  sched_.setStatic(n, isStatic);
  if (shard_) shard_->staticChanged(placement_.self, isStatic ? 1 : -1);
}

void Machine::placeNode(Opcode op, NodeId n, Value arg) {
  if (!shard_) {
    if (n >= db_->nodeCount())
      throw RuntimeError("coordination fact for node " + nodeName(n) + ", which does not exist");
    // One thread: the node stays where it is and is pinned; just-moved arrives at once (§5.7).
    setStatic(n, true);
    if (tables_.justMoved != Program::kNoPred) send(running_, n, tables_.justMoved, kNoArgs, false);
    return;
  }
  const char* what = op == Opcode::SET_CPU ? "set-cpu" : "set-affinity";
  const ThreadId owner = ownerOf(n);
  if (owner == kNoThread)
    throw RuntimeError(std::string(what) + " for node " + nodeName(n) + ", which does not exist");
  ThreadId target = kNoThread;
  if (op == Opcode::SET_CPU) {
    target = arg.asThread();
    if (target >= placement_.threads)
      throw RuntimeError("set-cpu: thread #T" + std::to_string(target) + " does not exist");
  } else {
    target = ownerOf(arg.asNode());
    if (target == kNoThread)
      throw RuntimeError("set-affinity: node " + nodeName(arg.asNode()) + " does not exist");
  }
  // Another thread: the node moves there at the next rebalance (its facts go to that shard),
  // where it is pinned and just-moved is added when it arrives (§5.7).
  if (owner != target) {
    if (n >= initialNodes_)
      throw RuntimeError(
          std::string(what) + ": node " + nodeName(n) +
          " is a thread node or was created by exists; only the graph's nodes move between threads");
    return shard_->requestMove(n, target);
  }
  if (owner == placement_.self)
    setStatic(n, true);
  else
    shard_->coordinateRemote(owner, Opcode::SET_STATIC, n, 0.0);
  if (tables_.justMoved != Program::kNoPred) send(running_, n, tables_.justMoved, kNoArgs, false);
}

Value Machine::programArg(std::uint32_t k) const {
  if (k == 0 || k > args_.size())
    throw RuntimeError("program argument @arg" + std::to_string(k) + " was not given (pass it after `--`)");
  const Value v = args_[k - 1];
  const_cast<Heap&>(heap_).retain(TypeTable::kString, v);
  return v;
}

std::int32_t Machine::staticNodes(ThreadId t) const {
  if (shard_) return shard_->staticNodes(t);
  std::int32_t count = 0;
  for (NodeId n = 0; n < db_->nodeCount(); ++n) count += sched_.isStatic(n);
  return count;
}
}  // namespace meldvm
