// Rule heads (§5.3): derived facts (DERIVE at the host, SEND elsewhere, SEND_DELAY with a delay,
// SEND_THREAD for thread facts), actions, coordination instructions, in-place updates,
// assignments, `exists`, conditionals, comprehensions and aggregate constructs.
#include <climits>

#include "lower_rule.hpp"

namespace meldc {

using namespace meldc::ast;
using meldvm::Opcode;
using meldvm::TypeId;
using meldvm::TypeTable;

bool RuleLowering::assignment(const Term& t) {
  if (t.kind != TermKind::Constraint || t.cond.kind != ExprKind::Compare || t.cond.op != BinOp::Eq)
    return false;
  const Expr& lhs = t.cond.args.at(0);
  if (lhs.kind != ExprKind::Var || ex.env.count(lhs.name)) return false;
  ex.env[lhs.name] = ex.value(t.cond.args.at(1));
  return true;
}

void RuleLowering::instruction(const Term& t, Instruction which) {
  std::vector<Reg> regs;
  std::vector<TypeId> types = {TypeTable::kNode};
  switch (which) {
    case Instruction::SetPriority:
    case Instruction::AddPriority:
    case Instruction::SetDefaultPriority:
      types.push_back(TypeTable::kFloat);
      break;
    case Instruction::SetAffinity:
      types.push_back(TypeTable::kNode);
      break;
    case Instruction::SetCpu:
      types.push_back(TypeTable::kThread);
      break;
    default:
      break;
  }
  if (t.args.size() != types.size()) throw LowerError(t.loc, "internal error: instruction arity");
  if (t.delayMs)
    throw LowerError(
        t.loc, "'" + t.name + "' is an instruction: it acts when the head runs and takes no delay ('@+...')");
  for (size_t i = 0; i < t.args.size(); ++i) regs.push_back(ex.valueAs(t.args[i], types[i]));
  static const std::map<Instruction, Opcode> ops = {
      {Instruction::SetPriority, Opcode::SET_PRIORITY},
      {Instruction::AddPriority, Opcode::ADD_PRIORITY},
      {Instruction::RemovePriority, Opcode::REMOVE_PRIORITY},
      {Instruction::SetDefaultPriority, Opcode::SET_DEFAULT_PRIORITY},
      {Instruction::ScheduleNext, Opcode::SCHEDULE_NEXT},
      {Instruction::SetStatic, Opcode::SET_STATIC},
      {Instruction::SetMoving, Opcode::SET_MOVING},
      {Instruction::SetAffinity, Opcode::SET_AFFINITY},
      {Instruction::SetCpu, Opcode::SET_CPU},
      {Instruction::StopProgram, Opcode::STOP_PROGRAM}};
  cb_.op(ops.at(which));
  for (Reg r : regs) cb_.w(r);
}

void RuleLowering::subgoal(const Term& t, std::optional<std::int64_t> localNode) {
  const PredInfo* p = L_.pred(t.sym);
  if (!p) throw LowerError(t.loc, "internal error: unknown predicate '" + t.name + "'");
  if (p->instruction != Instruction::None) return instruction(t, p->instruction);
  const meldvm::PredicateDesc& desc = L_.desc(*p);
  if (t.args.size() != desc.fields.size() + 1) throw LowerError(t.loc, "internal error: predicate arity");
  std::vector<Reg> regs;
  for (size_t i = 1; i < t.args.size(); ++i) regs.push_back(ex.valueAs(t.args[i], desc.fields[i - 1]));
  const Expr& home = t.args[0];
  if (desc.thread) {  // stored at the thread node of the thread the home names (§6.12)
    if (t.delayMs)
      throw LowerError(
          t.loc, "a delay ('@+...') on the thread fact '" + t.name +
                     "': thread facts are delivered at once (§5.3.1: the reference VM stops on a delayed "
                     "send to a thread)");
    const Reg to = ex.valueAs(home, TypeTable::kThread);  // may emit code: before the opcode
    cb_.op(Opcode::SEND_THREAD).w(p->id).w(to).regs(regs);
    return;
  }
  const bool atHost = (home.kind == ExprKind::Var && home.name == hostVar_ && ex.env.count(home.name) &&
                       ex.env[home.name] == host_) ||
                      (localNode && home.kind == ExprKind::Node && home.intValue == *localNode);
  if (atHost && !desc.action && !t.delayMs) {
    cb_.op(Opcode::DERIVE).w(p->id).regs(regs);
    return;
  }
  Reg to = ex.valueAs(home, TypeTable::kNode);
  if (t.delayMs && (*t.delayMs < 0 || *t.delayMs > INT32_MAX))
    throw LowerError(t.loc, "a delay longer than 2147483647 ms");
  if (desc.action && !t.delayMs) {
    cb_.op(Opcode::ACTION).w(p->id).w(to).regs(regs);
  } else if (t.delayMs) {  // a delayed action runs on the sending block after the delay (robots)
    cb_.op(Opcode::SEND_DELAY).w(p->id).w(to).w(std::uint32_t(*t.delayMs)).regs(regs);
  } else {
    cb_.op(Opcode::SEND).w(p->id).w(to).regs(regs);
  }
}

void RuleLowering::head(const std::vector<Term>& items, const BodyPlan* plan, std::uint32_t nextSlot,
                        std::uint32_t firstSlot) {
  for (const Term& t : items) {
    if (plan && plan->dropped.count(&t)) continue;
    if (plan && plan->updateHead == &t) {
      const meldvm::PredicateDesc& desc = L_.desc(*L_.pred(t.sym));
      std::vector<Reg> regs;
      for (size_t i = 1; i < t.args.size(); ++i) regs.push_back(ex.valueAs(t.args[i], desc.fields.at(i - 1)));
      const std::uint32_t flags = plan->moveToBack ? std::uint32_t(meldvm::kUpdateMoveToBack) : 0u;
      cb_.op(Opcode::UPDATE).w(firstSlot + std::uint32_t(plan->updateIndex)).w(flags).regs(regs);
      continue;
    }
    switch (t.kind) {
      case TermKind::Subgoal:
        subgoal(t);
        break;
      case TermKind::Constraint:
        if (!assignment(t))
          throw LowerError(
              t.loc,
              "a condition cannot stand in a head: a head holds facts, assignments 'X = e' of a new "
              "variable, comprehensions, aggregates, 'exists' and '(if ... end)' (§5.3)");
        break;
      case TermKind::Exists:
        for (const VarDecl& v : t.vars) {
          Reg r = cb_.reg(TypeTable::kNode);
          cb_.emit(Opcode::NEWNODE, {r});
          ex.env[v.name] = r;
        }
        head(t.head, nullptr, nextSlot);
        break;
      case TermKind::Conditional: {
        Label otherwise = cb_.label(), done = cb_.label();
        ex.jumpIfFalse(t.cond, otherwise);
        auto saved = ex.env;
        head(t.head, nullptr, nextSlot);
        ex.env = saved;
        cb_.op(Opcode::JMP).to(done);
        cb_.place(otherwise);
        head(t.elseHead, nullptr, nextSlot);
        ex.env = saved;
        cb_.place(done);
        break;
      }
      case TermKind::Comprehension:
        comprehension(t, nextSlot);
        break;
      case TermKind::Aggregate:
        aggregate(t, nextSlot);
        break;
    }
  }
}

void RuleLowering::comprehension(const Term& t, std::uint32_t slot) {
  BodyPlan plan = planBody(L_, t.body, t.head, hostVar_, std::nullopt, false);
  auto saved = ex.env;
  Label end = cb_.label();
  const auto inner = slot + std::uint32_t(plan.subgoals.size());
  match(plan, slot, end, Mode::Comprehension, false, [&] { head(t.head, &plan, inner, slot); });
  cb_.place(end);
  ex.env = saved;
}

void RuleLowering::aggregate(const Term& t, std::uint32_t slot) {
  BodyPlan plan = planBody(L_, t.body, t.perMatch, hostVar_, std::nullopt, false);
  struct Acc {
    const AggSpec* spec;
    Reg acc, one;
    TypeId item;
  };
  std::vector<Acc> accs;
  // The accumulators start before the loops (§5.3.4).
  for (const AggSpec& s : t.specs) {
    auto it = L_.typing.aggItems.find(&s);
    if (it == L_.typing.aggItems.end()) throw LowerError(s.loc, "internal error: aggregate without a type");
    Acc a{&s, 0, 0, L_.vmType(it->second)};
    switch (s.op) {
      case AggOp::Sum:
        a.acc = cb_.reg(a.item);
        if (a.item == TypeTable::kFloat)
          cb_.op(Opcode::MOVF).w(a.acc).dbl(0.0);
        else
          cb_.emit(Opcode::MOVI, {a.acc, 0});
        break;
      case AggOp::Count:
        a.acc = cb_.reg(TypeTable::kInt);
        a.one = cb_.reg(TypeTable::kInt);
        cb_.emit(Opcode::MOVI, {a.acc, 0});
        cb_.emit(Opcode::MOVI, {a.one, 1});
        break;
      case AggOp::Collect:
        a.acc = cb_.reg(L_.prog.types.list(a.item));
        cb_.emit(Opcode::NIL, {a.acc});
        break;
      case AggOp::Min:
        a.acc = cb_.reg(TypeTable::kInt);
        cb_.emit(Opcode::MOVI, {a.acc, std::uint32_t(INT32_MAX)});
        break;
      case AggOp::Custom:
        a.acc = cb_.reg(a.item);
        ex.into(s.start, a.acc);
        break;
    }
    accs.push_back(a);
  }
  auto saved = ex.env;
  Label end = cb_.label();
  const auto inner = slot + std::uint32_t(plan.subgoals.size());
  match(plan, slot, end, Mode::Comprehension, false, [&] {
    head(t.perMatch, &plan, inner, slot);
    for (const Acc& a : accs) {
      Reg v = a.spec->op == AggOp::Count ? a.one : ex.env.at(a.spec->var);
      switch (a.spec->op) {
        case AggOp::Sum:
          cb_.emit(a.item == TypeTable::kFloat ? Opcode::ADDF : Opcode::ADDI, {a.acc, a.acc, v});
          break;
        case AggOp::Count:
          cb_.emit(Opcode::ADDI, {a.acc, a.acc, v});
          break;
        case AggOp::Collect:
          cb_.emit(Opcode::CONS, {a.acc, v, a.acc, cb_.typeOf(a.acc)});
          break;
        case AggOp::Min:
          cb_.emit(Opcode::MINI, {a.acc, a.acc, v});
          break;
        case AggOp::Custom: {
          Reg r = ex.callRegs(a.spec->functionSym, {a.acc, v}, a.spec->loc, a.item);
          cb_.emit(Opcode::MOV, {a.acc, r});
          break;
        }
      }
    }
  });
  cb_.place(end);
  ex.env = saved;
  // The final head sees each spec variable bound to its aggregated value (even with no match);
  // after it the names are free again, for the rest of the rule's head (§5.3.4).
  for (const Acc& a : accs) ex.env[a.spec->var] = a.acc;
  head(t.head, nullptr, slot);
  ex.env = saved;
}

}  // namespace meldc
