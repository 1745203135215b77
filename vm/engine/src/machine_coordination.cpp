// The Machine's coordination facts (§5.7) and what the built-ins ask of the scheduler.
#include "meldvm/arith.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

namespace {
const Value kNoArgs[1] = {};  // arguments of just-moved (home only)
}  // namespace

void Machine::priorityRequest(NodeId n, double p) {
  if (n == running_ && inRun_) return;  // §5.7: ignored for the running node
  priorityRequests_.emplace_back(n, p);
}

void Machine::applyPriorityRequests() {
  for (const auto& [n, p] : priorityRequests_) sched_.setPriority(n, p);
  priorityRequests_.clear();
}

void Machine::coordination(Opcode op, NodeId n, double value) {
  if (n >= db_->nodeCount())
    throw RuntimeError("coordination fact for node @" + std::to_string(n) + ", which does not exist");
  switch (op) {
    case Opcode::ADD_PRIORITY:
      if (!(n == running_ && inRun_)) sched_.addPriority(n, value);
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
      sched_.setStatic(n, true);
      break;
    case Opcode::SET_MOVING:
      sched_.setStatic(n, false);
      break;
    case Opcode::SET_AFFINITY:
    case Opcode::SET_CPU:
      // One thread: the node stays where it is and is pinned; just-moved arrives at once (§5.7).
      sched_.setStatic(n, true);
      if (tables_.justMoved != Program::kNoPred) send(running_, n, tables_.justMoved, kNoArgs, false);
      break;
    default:
      break;
  }
}

Value Machine::programArg(std::uint32_t k) const {
  if (k == 0 || k > args_.size())
    throw RuntimeError("program argument @arg" + std::to_string(k) + " was not given (pass it after `--`)");
  const Value v = args_[k - 1];
  const_cast<Heap&>(heap_).retain(TypeTable::kString, v);
  return v;
}

std::int32_t Machine::staticNodes(ThreadId) const {
  std::int32_t count = 0;
  for (NodeId n = 0; n < db_->nodeCount(); ++n) count += sched_.isStatic(n);
  return count;
}
}  // namespace meldvm
