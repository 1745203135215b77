// Match plans (§6.4.3): one loop per body subgoal in match order; arguments become LOADs (new
// variables) or TESTs (bound values); constraints and assignments are emitted as soon as all
// their variables are bound; a failing test jumps to the NEXT of the innermost loop.
#include <set>

#include "lower_rule.hpp"
#include "meldc/ast/expr_vars.hpp"

namespace meldc {

using namespace meldc::ast;
using meldvm::Opcode;
using meldvm::TypeId;

namespace {

// The variables a subgoal argument binds (its pattern part).
void patternVars(const Expr& e, std::set<std::string>& out) {
  forEachPatternVar(
      e, [&](const Expr& v) { out.insert(v.name); }, [](const Expr&) {});
}

bool isPattern(const Expr& e) { return e.kind == ExprKind::List || e.kind == ExprKind::Struct; }

}  // namespace

void RuleLowering::bindHost() {
  if (hostVar_.empty()) return;  // only thread facts: the rule runs at the thread node (§6.12)
  host_ = cb_.reg(meldvm::TypeTable::kNode);
  cb_.emit(Opcode::HOST, {host_});
  ex.env[hostVar_] = host_;
}

void RuleLowering::flush(Label fail) {
  for (bool progress = true; progress;) {
    progress = false;
    for (Pending& p : pending_) {
      if (p.done) continue;
      if (p.expr) {  // deferred pattern test
        if (!ex.bound(*p.expr)) continue;
        ex.testEqual(p.reg, *p.expr, fail);
      } else if (p.isAssignment) {
        const Expr& rhs = p.term->cond.args.at(1);
        if (!ex.bound(rhs)) continue;
        ex.env[p.term->cond.args.at(0).name] = ex.value(rhs);
      } else if (p.term->kind == TermKind::Constraint) {
        if (!ex.bound(p.term->cond)) continue;
        ex.jumpIfFalse(p.term->cond, fail);
      } else {  // a boolean function call written like a subgoal
        bool ready = true;
        for (const Expr& a : p.term->args) ready &= ex.bound(a);
        if (!ready) continue;
        Reg r = ex.call(p.term->sym, p.term->args, p.term->loc, meldvm::TypeTable::kBool);
        cb_.op(Opcode::JF).w(r).to(fail);
      }
      p.done = progress = true;
    }
  }
}

void RuleLowering::destructure(Reg r, const Expr& pat, Label fail) {
  const meldvm::TypeTable& types = L_.prog.types;
  switch (pat.kind) {
    case ExprKind::Anon:
      return;
    case ExprKind::Var:
      if (!ex.env.count(pat.name)) {
        ex.env[pat.name] = r;
        return;
      }
      break;
    case ExprKind::List: {
      if (pat.args.empty()) break;  // [] : a nil test below
      const TypeId listType = cb_.typeOf(r), elem = types.element(listType);
      size_t n = pat.args.size() - (pat.hasTail ? 1 : 0);
      Reg cur = r;
      for (size_t i = 0; i < n; ++i) {
        cb_.op(Opcode::JNIL).w(cur).to(fail);
        Reg h = cb_.reg(elem), t = cb_.reg(listType);
        cb_.emit(Opcode::HEAD, {h, cur});
        cb_.emit(Opcode::TAIL, {t, cur});
        destructure(h, pat.args[i], fail);
        cur = t;
      }
      if (pat.hasTail)
        destructure(cur, pat.args.back(), fail);
      else
        cb_.op(Opcode::JNOTNIL).w(cur).to(fail);
      return;
    }
    case ExprKind::Struct: {
      const auto span = types.fields(cb_.typeOf(r));
      const std::vector<TypeId> fields(span.begin(), span.end());
      for (size_t i = 0; i < pat.args.size() && i < fields.size(); ++i) {
        Reg f = cb_.reg(fields[i]);
        cb_.emit(Opcode::FIELD, {f, r, std::uint32_t(i)});
        destructure(f, pat.args[i], fail);
      }
      return;
    }
    default:
      break;
  }
  if (ex.bound(pat))
    ex.testEqual(r, pat, fail);
  else  // its variables are bound by a later subgoal or assignment
    pending_.push_back(Pending{nullptr, r, &pat, false, false});
}

void RuleLowering::threadHome(const Expr& home, Label fail) {
  // With one VM thread every thread fact a node sees belongs to the running thread (§6.12), so the
  // home variable is that thread: bound here, or compared with it when already bound.
  if (home.kind != ExprKind::Var) return;
  Reg t = cb_.reg(meldvm::TypeTable::kThread);
  cb_.emit(Opcode::THREAD, {t});
  auto it = ex.env.find(home.name);
  if (it == ex.env.end()) {
    ex.env[home.name] = t;
    return;
  }
  Reg same = cb_.reg(meldvm::TypeTable::kBool);
  cb_.emit(Opcode::EQ, {same, it->second, t, meldvm::TypeTable::kThread});
  cb_.op(Opcode::JF).w(same).to(fail);
}

void RuleLowering::pattern(std::uint32_t slot, std::uint32_t field, TypeId type, const Expr& arg,
                           Label fail) {
  if (arg.kind == ExprKind::Anon) return;
  if (arg.kind == ExprKind::Var && ignored_.count(arg.name) && !ex.env.count(arg.name)) return;
  const bool newVar = arg.kind == ExprKind::Var && !ex.env.count(arg.name);
  if (newVar || isPattern(arg) || !ex.bound(arg)) {
    Reg r = cb_.reg(type);
    cb_.emit(Opcode::LOAD, {slot, field, r});
    destructure(r, arg, fail);
    return;
  }
  Reg v = ex.valueAs(arg, type);
  cb_.op(Opcode::TEST).w(slot).w(field).w(v).to(fail);
}

std::optional<std::uint32_t> RuleLowering::indexedKey(const SubgoalPlan& s) {
  const meldvm::PredicateDesc& desc = L_.desc(*s.pred);
  if (desc.thread || desc.aggregated()) return std::nullopt;
  for (const meldvm::IndexRequest& ix : L_.prog.indexes) {
    if (ix.predicate != s.pred->id || ix.field + 1 >= s.term->args.size()) continue;
    const Expr& arg = s.term->args[ix.field + 1];
    const TypeId t = desc.fields[ix.field];
    // Keys the index compares by their bits, as the TEST it replaces would: scalars, not floats.
    using meldvm::TypeTable;
    const bool scalar = t == TypeTable::kInt || t == TypeTable::kNode || t == TypeTable::kBool;
    const bool bound = arg.kind == ExprKind::Var
                           ? ex.env.count(arg.name) > 0
                           : !isPattern(arg) && arg.kind != ExprKind::Anon && ex.bound(arg);
    if (scalar && bound) return ix.field;
  }
  return std::nullopt;
}

void RuleLowering::match(const BodyPlan& plan, std::uint32_t firstSlot, Label outerFail, Mode mode,
                         bool prebound, const std::function<void()>& onMatch) {
  std::vector<Pending> saved = std::move(pending_);
  pending_.clear();
  // Assignments (§5.2): `X = e` with X bound by no subgoal (nor outside) defines X.
  std::set<std::string> patternBound;
  for (const auto& [name, reg] : ex.env) patternBound.insert(name);
  for (const SubgoalPlan& s : plan.subgoals)
    for (const Expr& a : s.term->args) patternVars(a, patternBound);
  for (const Term* t : plan.conditions) {
    Pending p;
    p.term = t;
    if (t->kind == TermKind::Constraint && t->cond.kind == ExprKind::Compare && t->cond.op == BinOp::Eq &&
        t->cond.args.at(0).kind == ExprKind::Var && !patternBound.count(t->cond.args[0].name)) {
      p.isAssignment = true;
      patternBound.insert(t->cond.args[0].name);
    }
    pending_.push_back(p);
  }
  flush(outerFail);

  struct Loop {
    Label next, after;
  };
  std::vector<Loop> loops;
  bool consumableAbove = false;
  for (size_t i = 0; i < plan.subgoals.size(); ++i) {
    const SubgoalPlan& s = plan.subgoals[i];
    const std::uint32_t slot = firstSlot + std::uint32_t(i);
    const meldvm::PredicateDesc& desc = L_.desc(*s.pred);
    cb_.useSlot(slot);
    Label fail = outerFail;
    if (!(prebound && i == 0)) {
      std::uint32_t flags = 0;
      if (s.linear) flags |= meldvm::kIterLinear;
      if (s.thread) flags |= meldvm::kIterThread;
      if (s.consumed()) flags |= meldvm::kIterConsume;
      if (s.consumableClass()) flags |= meldvm::kIterConsumableClass;
      if (mode == Mode::Rule && consumableAbove) flags |= meldvm::kIterReturnOnFire;
      Loop loop{cb_.label(), cb_.label()};
      std::optional<std::uint32_t> sortField;
      keyField.reset();
      if (plan.selector) {
        for (size_t a = 1; a < s.term->args.size(); ++a) {
          const Expr& arg = s.term->args[a];
          if (arg.kind == ExprKind::Var && arg.name == plan.selector->var) sortField = std::uint32_t(a - 1);
        }
        std::set<std::string> vars;
        for (size_t a = 1; a < s.term->args.size(); ++a) ExprLowerer::variables(s.term->args[a], vars);
        if (!sortField && vars.count(plan.selector->var))
          throw LowerError(s.term->loc, "a selector orders the facts by an argument (§5.4): '" +
                                            plan.selector->var + "' must be an argument of '" + s.term->name +
                                            "', not inside a list or struct");
      }
      if (sortField) {
        if (plan.selector->kind == SelectorKind::Random) flags |= meldvm::kIterRandom;
        cb_.op(Opcode::ITER_SORTED).w(s.pred->id).w(slot).w(flags).w(*sortField).to(loop.after);
      } else if (std::optional<std::uint32_t> field = indexedKey(s)) {
        // `index p/N` (§4.4) on an argument already bound here: the loop visits only the facts
        // with that key, through the store's index, instead of testing every fact of the node.
        const Reg key = ex.valueAs(s.term->args[*field + 1], desc.fields[*field]);
        cb_.op(Opcode::ITER_KEY).w(s.pred->id).w(slot).w(flags).w(*field).w(key).to(loop.after);
        keyField = field;
      } else {
        cb_.op(Opcode::ITER).w(s.pred->id).w(slot).w(flags).to(loop.after);
      }
      loops.push_back(loop);
      fail = loop.next;
    }
    consumableAbove |= s.consumableClass();
    if (s.thread) threadHome(s.term->args[0], fail);
    for (size_t a = 1; a < s.term->args.size(); ++a)
      if (!(keyField && *keyField == a - 1 && !(prebound && i == 0)))  // the index matched it already
        pattern(slot, std::uint32_t(a - 1), desc.fields.at(a - 1), s.term->args[a], fail);
    keyField.reset();
    flush(fail);
  }
  for (const Pending& p : pending_)
    if (!p.done)
      throw LowerError(p.term ? p.term->loc : p.expr->loc,
                       "internal error: a condition whose variables are never bound");
  pending_ = std::move(saved);

  onMatch();
  // A body without loops (a persistent process matching only its trigger, a comprehension without
  // facts) has nothing to fire: its code simply runs once.
  if (!loops.empty()) cb_.emit(mode == Mode::Rule ? Opcode::FIRE : Opcode::CFIRE, {firstSlot});
  for (size_t i = loops.size(); i-- > 0;) {
    cb_.place(loops[i].next);
    cb_.op(Opcode::NEXT);
    cb_.place(loops[i].after);
  }
}

}  // namespace meldc
