// Start-up code (§6.2): rule 0 (`_init -o axioms`: the host's constant axioms through AXIOMS, then
// the variable axioms in program order), with thread predicates rule 1 (`_init_thread -o thread
// axioms`: the variable axioms of thread predicates, §6.12) and one axiom block per initial node
// holding its constant axioms: those needing evaluation in reverse source order, then the purely
// literal facts grouped by predicate (groups in order of first occurrence, source order within a
// group; a group's ground facts of int, float, bool and node fields as one AXIOM_FACTS).
#include <algorithm>
#include <bit>
#include <functional>
#include <map>
#include <optional>
#include <set>

#include "lower_rule.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldc {

using namespace meldc::ast;
using meldvm::Opcode;

namespace {

// A constant axiom: a fact of a statement, or a ground fact (ast/ground_fact.hpp).
struct Axiom {
  const Rule* statement = nullptr;
  const Term* fact = nullptr;
  const GroundFact* ground = nullptr;
};

bool literal(const Lowering& L, const Expr& e) {
  switch (e.kind) {
    case ExprKind::Int:
    case ExprKind::Float:
    case ExprKind::Bool:
    case ExprKind::String:
    case ExprKind::Node:
      return true;
    case ExprKind::Const:
      return L.folded.count(e.sym) > 0;
    case ExprKind::List:
    case ExprKind::Struct:
      return std::all_of(e.args.begin(), e.args.end(), [&](const Expr& a) { return literal(L, a); });
    default:
      return false;
  }
}

std::vector<const Term*> conditions(const Rule& r) {
  std::vector<const Term*> out;
  for (const std::vector<Term>* items : {&r.body, &r.head})
    for (const Term& t : *items)
      if (t.kind == TermKind::Constraint) out.push_back(&t);
  return out;
}

// The statement's assignments (in dependency order) and constraints; a false constraint skips to
// `skip` (this axiom only).
void evaluateConditions(RuleLowering& rl, CodeBuilder& cb, const Rule& r, CodeBuilder::Label skip) {
  std::vector<const Term*> todo = conditions(r);
  for (bool progress = true; progress;) {
    progress = false;
    for (auto it = todo.begin(); it != todo.end();) {
      const Term& t = **it;
      const Expr& lhs = t.cond.args.empty() ? t.cond : t.cond.args[0];
      const bool isAssignment = t.cond.kind == ExprKind::Compare && t.cond.op == BinOp::Eq &&
                                lhs.kind == ExprKind::Var && !rl.ex.env.count(lhs.name);
      if (isAssignment ? rl.ex.bound(t.cond.args.at(1)) : rl.ex.bound(t.cond)) {
        if (!isAssignment || !rl.assignment(t)) rl.ex.jumpIfFalse(t.cond, skip);
        it = todo.erase(it);
        progress = true;
      } else {
        ++it;
      }
    }
  }
  (void)cb;
  if (!todo.empty()) throw LowerError(todo.front()->loc, "internal error: axiom condition never bound");
}

// §3.1: a node literal has the subtype of the places it is used at (the home or a field declared
// with that subtype). Returns subtype name (lower case) -> internal ids of its nodes.
std::map<Symbol, std::set<std::int64_t>> subtypeNodes(const Lowering& L) {
  std::map<Symbol, std::set<std::int64_t>> out;
  std::function<void(const std::vector<Term>&)> walk = [&](const std::vector<Term>& terms) {
    for (const Term& t : terms) {
      if (t.kind == TermKind::Subgoal)
        if (const PredInfo* p = L.pred(t.sym); p && p->decl)
          for (size_t i = 0; i < t.args.size() && i < p->decl->fields.size(); ++i) {
            const TypeExpr& type = p->decl->fields[i].type;
            if (t.args[i].kind == ExprKind::Node && type.kind == TypeKind::Named)
              out[type.sym].insert(t.args[i].intValue);
          }
      walk(t.body);
      walk(t.perMatch);
      walk(t.head);
      walk(t.elseHead);
    }
  };
  for (const Rule& r : L.ast.rules) {
    walk(r.body);
    walk(r.head);
  }
  return out;
}

// Jumps to `skip` unless the host is one of `nodes` (nodes created by `exists` have no subtype).
void guardSubtype(CodeBuilder& cb, Reg host, const std::set<std::int64_t>& nodes, CodeBuilder::Label skip) {
  CodeBuilder::Label ok = cb.label();
  for (std::int64_t n : nodes) {
    Reg r = cb.reg(meldvm::TypeTable::kNode), b = cb.reg(meldvm::TypeTable::kBool);
    cb.emit(Opcode::MOVN, {r, std::uint32_t(n)});
    cb.emit(Opcode::EQ, {b, host, r, meldvm::TypeTable::kNode});
    cb.op(Opcode::JT).w(b).to(ok);
  }
  cb.op(Opcode::JMP).to(skip);
  cb.place(ok);
}

bool isAlias(const Lowering& L, const TypeExpr& t) {
  for (const TypeAliasDecl& a : L.ast.typeAliases)
    if (a.sym == t.sym) return true;
  return false;
}

void checkFactOnly(const Rule& r) {
  for (const Term& t : r.head)
    if (t.kind != TermKind::Subgoal && t.kind != TermKind::Constraint)
      throw LowerError(
          t.loc,
          "a fact (a statement without body facts, §5.1) holds facts, constraints and assignments "
          "only: this needs a rule");
}

// A fact of a thread predicate whose home is not a node literal: instantiated in every thread node
// by rule 1 (§6.2, §6.12) instead of in every node by rule 0.
bool isThreadFact(const Lowering& L, const Term& t) {
  const PredInfo* p = L.pred(t.sym);
  return p && p->id != meldvm::Program::kNoPred && L.desc(*p).thread &&
         (t.args[0].kind == ExprKind::Var || t.args[0].kind == ExprKind::Thread);
}

// Rules 0 and 1 share one frame: a loop over the start-up fact whose body derives the axioms
// and fires once.
struct InitLoop {
  CodeBuilder::Label next, end;
};
InitLoop openInitLoop(CodeBuilder& cb, meldvm::PredId init, std::uint32_t extraFlags) {
  InitLoop loop{cb.label(), cb.label()};
  cb.useSlot(0);
  cb.op(Opcode::ITER)
      .w(init)
      .w(0)
      .w(meldvm::kIterLinear | meldvm::kIterConsume | meldvm::kIterConsumableClass | extraFlags)
      .to(loop.end);
  return loop;
}
meldvm::Rule closeInitLoop(CodeBuilder& cb, const InitLoop& loop, meldvm::PredId init, const char* label) {
  cb.emit(Opcode::FIRE, {0});
  cb.place(loop.next);
  cb.op(Opcode::NEXT);
  cb.place(loop.end);
  cb.op(Opcode::RET);
  meldvm::Rule rule;
  rule.block = cb.finish(label);
  rule.bodyPredicates = {init};
  return rule;
}

struct ThreadAxioms {
  const Rule* statement;
  std::vector<const Term*> facts;
};

// Rule 1 (§6.2): `_init_thread -o thread axioms`, run on the thread node. The loop carries
// kIterThread so that the VM iterates the thread node's `_init_thread` fact; every variable home
// stands for that thread.
meldvm::Rule threadInitRule(Lowering& L, const std::vector<ThreadAxioms>& axioms) {
  CodeBuilder cb;
  const PredInfo* init = L.builtinPred("_init_thread");
  if (!init) throw LowerError({}, "internal error: thread predicates without _init_thread");
  const InitLoop loop = openInitLoop(cb, init->id, meldvm::kIterThread);
  const Reg self = cb.reg(meldvm::TypeTable::kThread);
  cb.emit(Opcode::THREAD, {self});
  for (const ThreadAxioms& a : axioms) {
    try {
      L.at(cb, a.statement->loc);
      RuleLowering rl(L, cb, "");
      for (const Term* t : a.facts)
        if (t->args[0].kind == ExprKind::Var) rl.ex.env[t->args[0].name] = self;
      CodeBuilder::Label skip = cb.label();
      evaluateConditions(rl, cb, *a.statement, skip);
      for (const Term* t : a.facts) rl.subgoal(*t);
      cb.place(skip);
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
  }
  return closeInitLoop(cb, loop, init->id, "_init_thread -o thread axioms");
}

// The internal id of a home argument known at compile time: a node literal or a `const` that
// folds to one (`const start = @3.` then `path(start, 0).`, §4.6).
std::optional<std::int64_t> constantNode(Lowering& L, const Expr& home) {
  if (home.kind == ExprKind::Node) return home.intValue;
  if (home.kind != ExprKind::Const) return std::nullopt;
  std::optional<Folded> f = foldConstant(L, home);
  if (!f || f->kind != Folded::Node) return std::nullopt;
  return f->i;
}

// A fact whose home is a node-valued expression known only at run time (a global computed at
// start-up, a call): rule 0 evaluates it on every node and derives the fact on the node it names,
// so the fact lands where a constant axiom with that home would.
void computedHomeAxiom(Lowering& L, CodeBuilder& cb, const Rule& r, const Term& t) {
  RuleLowering rl(L, cb, "");
  const Reg host = cb.reg(meldvm::TypeTable::kNode);
  cb.emit(Opcode::HOST, {host});
  CodeBuilder::Label skip = cb.label();
  evaluateConditions(rl, cb, r, skip);
  const Reg home = rl.ex.valueAs(t.args[0], meldvm::TypeTable::kNode);
  const Reg same = cb.reg(meldvm::TypeTable::kBool);
  cb.emit(Opcode::EQ, {same, host, home, meldvm::TypeTable::kNode});
  cb.op(Opcode::JF).w(same).to(skip);
  rl.subgoal(t);
  cb.place(skip);
}

// A ground fact at its home: its literals in registers, then DERIVE, as RuleLowering::subgoal
// lowers the same fact written as a statement.
void groundAxiom(Lowering& L, CodeBuilder& cb, const GroundFact& f, const PredInfo& p) {
  const GroundFacts& facts = L.ast.groundFacts;
  const meldvm::PredicateDesc& desc = L.desc(p);
  std::vector<Reg> regs;
  regs.reserve(f.argCount);
  for (std::size_t i = 1; i < f.argCount; ++i) {
    const GroundArg& a = facts.arg(f, i);
    const meldvm::TypeId type = desc.fields.at(i - 1);
    const Reg r = cb.reg(type);
    switch (a.kind) {
      case GroundArg::Kind::Int:
        if (type == meldvm::TypeTable::kFloat)
          cb.op(Opcode::MOVF).w(r).dbl(double(a.i));
        else
          cb.emit(Opcode::MOVI, {r, std::uint32_t(std::int32_t(a.i))});
        break;
      case GroundArg::Kind::Float:
        cb.op(Opcode::MOVF).w(r).dbl(a.f);
        break;
      case GroundArg::Kind::Node:
        cb.emit(Opcode::MOVN, {r, std::uint32_t(a.i)});
        break;
      case GroundArg::Kind::String: {
        const std::string& text = L.sources.file(f.loc.file).text;
        cb.emit(Opcode::MOVS, {r, L.string(text.substr(a.offset + 1, a.length - 2u))});
        break;
      }
      case GroundArg::Kind::Bool:
        cb.emit(Opcode::MOVB, {r, a.i ? 1u : 0u});
        break;
    }
    regs.push_back(r);
  }
  cb.op(Opcode::DERIVE).w(p.id).regs(regs);
}

// A ground fact's literal as a folded constant (nothing for strings, which AXIOM_FACTS cannot hold).
std::optional<Folded> foldedLiteral(const GroundArg& g) {
  Folded v;
  switch (g.kind) {
    case GroundArg::Kind::Int:
      v.kind = Folded::Int, v.i = g.i;
      return v;
    case GroundArg::Kind::Float:
      v.kind = Folded::Float, v.f = g.f;
      return v;
    case GroundArg::Kind::Node:
      v.kind = Folded::Node, v.i = g.i;
      return v;
    case GroundArg::Kind::Bool:
      v.kind = Folded::Bool, v.b = g.i != 0;
      return v;
    case GroundArg::Kind::String:
      break;
  }
  return std::nullopt;
}

// One scalar field of AXIOM_FACTS (bytecode_internal.hpp's axiomFactWords) from a constant of the
// field's kind (an int may stand for a float); false for anything else.
bool packField(meldvm::TypeId field, const Folded& v, std::vector<std::uint32_t>& out) {
  switch (field) {
    case meldvm::TypeTable::kFloat: {
      if (v.kind != Folded::Float && v.kind != Folded::Int) return false;
      const auto bits = std::bit_cast<std::uint64_t>(v.kind == Folded::Int ? double(v.i) : v.f);
      out.push_back(std::uint32_t(bits));
      out.push_back(std::uint32_t(bits >> 32));
      return true;
    }
    case meldvm::TypeTable::kInt:
      if (v.kind != Folded::Int) return false;
      out.push_back(std::uint32_t(std::int32_t(v.i)));
      return true;
    case meldvm::TypeTable::kBool:
      if (v.kind != Folded::Bool) return false;
      out.push_back(v.b ? 1u : 0u);
      return true;
    case meldvm::TypeTable::kNode:
      if (v.kind != Folded::Node) return false;
      out.push_back(std::uint32_t(v.i));
      return true;
    default:
      return false;
  }
}

// Appends the data words of a literal axiom as one of AXIOM_FACTS' facts to `out`; false, and
// `out` as it was, when it cannot be one. A ground fact and the same fact written as a statement
// (meldc's plain path) give the same words, so that the compact path of ground facts stays
// invisible in the bytecode.
bool packFact(Lowering& L, const Axiom& a, const PredInfo* p, std::vector<std::uint32_t>& out) {
  if (!p || p->id == meldvm::Program::kNoPred || p->instruction != Instruction::None) return false;
  const meldvm::PredicateDesc& desc = L.desc(*p);
  if (desc.action || desc.thread || meldvm::detail::axiomFactWords(desc.fields) == 0) return false;
  const std::size_t mark = out.size();
  const auto field = [&](std::size_t i, const std::optional<Folded>& v) {
    return v && packField(desc.fields[i - 1], *v, out);
  };
  bool packed = true;
  if (a.ground) {
    const GroundFacts& facts = L.ast.groundFacts;
    packed = a.ground->argCount == desc.fields.size() + 1;
    for (std::size_t i = 1; packed && i < a.ground->argCount; ++i)
      packed = field(i, foldedLiteral(facts.arg(*a.ground, i)));
  } else {
    packed = conditions(*a.statement).empty() && a.fact->args.size() == desc.fields.size() + 1;
    for (std::size_t i = 1; packed && i < a.fact->args.size(); ++i)  // literal(): as nodeAxiomOrder decides
      packed = literal(L, a.fact->args[i]) && field(i, foldConstant(L, a.fact->args[i]));
  }
  if (!packed) out.resize(mark);
  return packed;
}

// Literal facts of one predicate in a row, as one AXIOM_FACTS: a data file's facts take a few words
// each instead of a DERIVE and a register per field, and load without an instruction per field.
// `words` holds the facts' words, the same number each; each fact's source line is in force from
// its first data word.
void packedAxioms(Lowering& L, CodeBuilder& cb, meldvm::PredId pred, const std::vector<SourceLoc>& locs,
                  const std::vector<std::uint32_t>& words) {
  const std::size_t per = words.size() / locs.size();
  L.at(cb, locs.front());
  cb.op(Opcode::AXIOM_FACTS).w(pred).w(std::uint32_t(words.size()));
  for (std::size_t i = 0; i < locs.size(); ++i) {
    L.at(cb, locs[i]);
    for (std::size_t k = i * per; k < (i + 1) * per; ++k) cb.w(words[k]);
  }
}

// The axioms of one node: those needing evaluation in reverse source order, then the literal
// facts grouped by predicate (groups in order of first occurrence, source order within a group).
std::vector<Axiom> nodeAxiomOrder(Lowering& L, const std::vector<Axiom>& axioms,
                                  const std::vector<Symbol>& groundNames) {
  std::vector<Axiom> evaluated;
  std::vector<std::pair<std::size_t, Axiom>> literals;  // group, axiom
  std::vector<Symbol> order;
  for (const Axiom& a : axioms) {
    Symbol name = a.ground ? groundNames[a.ground->name] : Symbol{};
    if (!a.ground) {
      const PredInfo* p = L.pred(a.fact->sym);
      bool isLiteral = p && p->instruction == Instruction::None && conditions(*a.statement).empty();
      for (size_t i = 1; i < a.fact->args.size() && isLiteral; ++i) isLiteral = literal(L, a.fact->args[i]);
      if (!isLiteral) {
        evaluated.push_back(a);
        continue;
      }
      name = a.fact->sym;
    }
    const std::size_t group = std::find(order.begin(), order.end(), name) - order.begin();
    if (group == order.size()) order.push_back(name);
    literals.emplace_back(group, a);
  }
  std::reverse(evaluated.begin(), evaluated.end());
  std::stable_sort(literals.begin(), literals.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  for (const auto& [group, a] : literals) evaluated.push_back(a);
  return evaluated;
}

}  // namespace

namespace {

// Axioms of constant homes, per node (internal id): in program order.
using ConstantAxioms = std::vector<std::vector<Axiom>>;

// One statement that is an axiom: its facts of variable and computed homes into rule 0 (`cb`),
// those of thread predicates to `threadAxioms`, those of constant homes to `constant`.
void statementAxioms(Lowering& L, CodeBuilder& cb, const Rule& r, ConstantAxioms& constant,
                     std::vector<ThreadAxioms>& threadAxioms,
                     std::map<Symbol, std::set<std::int64_t>>& subtypes) {
  checkFactOnly(r);
  std::vector<const Term*> variable, thread, computed;
  for (const Term& t : r.head) {
    if (t.kind != TermKind::Subgoal || t.args.empty()) continue;
    if (isThreadFact(L, t)) {
      thread.push_back(&t);
    } else if (std::optional<std::int64_t> node = constantNode(L, t.args[0])) {
      if (*node >= 0 && std::size_t(*node) < constant.size())
        constant[std::size_t(*node)].push_back(Axiom{&r, &t});
    } else if (t.args[0].kind == ExprKind::Var) {
      variable.push_back(&t);
    } else {
      computed.push_back(&t);
    }
  }
  if (!thread.empty()) threadAxioms.push_back(ThreadAxioms{&r, std::move(thread)});
  // Only a statement that puts code into rule 0 says where it comes from there (a fact of a
  // constant home, into its node's axiom block, must leave rule 0 as the compact path leaves it).
  if (!computed.empty() || !variable.empty()) L.at(cb, r.loc);
  for (const Term* t : computed) computedHomeAxiom(L, cb, r, *t);
  if (variable.empty()) return;
  // Every variable home stands for the node running rule 0.
  RuleLowering rl(L, cb, variable.front()->args[0].name);
  rl.bindHost();
  const Reg host = rl.ex.env.at(variable.front()->args[0].name);
  for (const Term* t : variable) rl.ex.env[t->args[0].name] = host;
  CodeBuilder::Label skip = cb.label();
  evaluateConditions(rl, cb, r, skip);
  for (const Term* t : variable) {
    // §6.2: only on the nodes of the predicate's subtype, if it has one.
    const PredInfo* p = L.pred(t->sym);
    const TypeExpr* home = p && p->decl ? &p->decl->fields.at(0).type : nullptr;
    const bool subtype = home && home->kind == TypeKind::Named &&
                         L.vmType(*home) == meldvm::TypeTable::kNode && !isAlias(L, *home);
    CodeBuilder::Label next = cb.label();
    if (subtype) guardSubtype(cb, host, subtypes[home->sym], next);
    rl.subgoal(*t);
    cb.place(next);
  }
  cb.place(skip);
}

// The axiom block of one node.
void nodeAxiomBlock(Lowering& L, std::int64_t node, const std::vector<Axiom>& axioms,
                    const std::vector<Symbol>& groundNames, const std::vector<const PredInfo*>& groundPreds) {
  CodeBuilder block;
  try {
    const std::vector<Axiom> order = nodeAxiomOrder(L, axioms, groundNames);
    const auto predOf = [&](const Axiom& a) {
      return a.ground ? groundPreds[a.ground->name] : L.pred(a.fact->sym);
    };
    std::vector<SourceLoc> runLocs;
    std::vector<std::uint32_t> runWords;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Axiom& a = order[k];
      const PredInfo* p = predOf(a);
      runLocs.clear();
      runWords.clear();
      for (std::size_t j = k; j < order.size() && predOf(order[j]) == p && packFact(L, order[j], p, runWords);
           ++j)
        runLocs.push_back(order[j].ground ? order[j].ground->loc : order[j].statement->loc);
      if (!runLocs.empty()) {
        packedAxioms(L, block, p->id, runLocs, runWords);
        k += runLocs.size() - 1;
        continue;
      }
      if (a.ground) {
        L.at(block, a.ground->loc);
        groundAxiom(L, block, *a.ground, *groundPreds[a.ground->name]);
        continue;
      }
      L.at(block, a.statement->loc);
      RuleLowering rl(L, block, "");
      CodeBuilder::Label skip = block.label();
      evaluateConditions(rl, block, *a.statement, skip);
      rl.subgoal(*a.fact, node);
      block.place(skip);
    }
    block.op(Opcode::RET);
    L.prog.nodeAxioms[size_t(node)] = std::uint32_t(L.prog.axiomBlocks.size());
    L.prog.axiomBlocks.push_back(block.finish("axioms of node " + std::to_string(node)));
  } catch (const LowerError& e) {
    L.diag.error(e.loc, e.what());
  }
}

}  // namespace

void lowerAxioms(Lowering& L) {
  const PredInfo* init = L.builtinPred("_init");
  if (!init) return;
  ConstantAxioms constant(L.prog.nodeAxioms.size());
  std::vector<ThreadAxioms> threadAxioms;  // for rule 1, in program order
  CodeBuilder cb;
  const InitLoop loop = openInitLoop(cb, init->id, 0);
  cb.op(Opcode::AXIOMS);
  std::map<Symbol, std::set<std::int64_t>> subtypes = subtypeNodes(L);
  const GroundFacts& ground = L.ast.groundFacts;
  const std::vector<Symbol>& groundNames = ground.nameSyms;
  std::vector<const PredInfo*> groundPreds;
  for (const Symbol n : groundNames) groundPreds.push_back(L.pred(n));  // admitted facts: declared
  forEachStatement(
      L.ast,
      [&](const Rule& r) {
        if (!isAxiom(L, r)) return;
        try {
          statementAxioms(L, cb, r, constant, threadAxioms, subtypes);
        } catch (const LowerError& e) {
          L.diag.error(e.loc, e.what());
        }
      },
      [&](const GroundFact& f) {
        const std::int64_t node = ground.arg(f, 0).i;
        if (node >= 0 && std::size_t(node) < constant.size())
          constant[std::size_t(node)].push_back(Axiom{nullptr, nullptr, &f});
      });
  L.prog.rules.insert(L.prog.rules.begin(), closeInitLoop(cb, loop, init->id, "_init -o axioms"));
  if (L.threads) {
    try {
      L.prog.rules.insert(L.prog.rules.begin() + 1, threadInitRule(L, threadAxioms));
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
  }
  for (std::size_t node = 0; node < constant.size(); ++node)
    if (!constant[node].empty())
      nodeAxiomBlock(L, std::int64_t(node), constant[node], groundNames, groundPreds);
}

}  // namespace meldc
