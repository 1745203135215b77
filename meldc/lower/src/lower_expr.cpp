#include "lower_expr.hpp"

#include "meldc/builtins.hpp"
#include "meldvm/builtin_signatures.hpp"

namespace meldc {

using namespace meldc::ast;
using meldvm::Opcode;
using meldvm::TypeId;
using meldvm::TypeKind;
using meldvm::TypeTable;

namespace {

bool isEmptyList(const Expr& e) { return e.kind == ExprKind::List && e.args.empty(); }

// `L = []` / `[] = L` / `L <> []`: the list operand of a nil test, or null.
const Expr* nilTest(const Expr& e) {
  if (e.kind != ExprKind::Compare || (e.op != BinOp::Eq && e.op != BinOp::Ne)) return nullptr;
  if (isEmptyList(e.args[1])) return &e.args[0];
  if (isEmptyList(e.args[0])) return &e.args[1];
  return nullptr;
}

}  // namespace

void ExprLowerer::variables(const Expr& e, std::set<std::string>& out) {
  if (e.kind == ExprKind::Var) {
    out.insert(e.name);
    return;
  }
  if (e.kind == ExprKind::Let) {
    variables(e.args.at(0), out);
    std::set<std::string> inner;
    variables(e.args.at(1), inner);
    inner.erase(e.name);
    out.insert(inner.begin(), inner.end());
    return;
  }
  for (const Expr& a : e.args) variables(a, out);
}

bool ExprLowerer::bound(const Expr& e) const {
  std::set<std::string> vars;
  variables(e, vars);
  for (const std::string& v : vars)
    if (!env.count(v)) return false;
  return true;
}

Reg ExprLowerer::folded(const Folded& f, TypeId want) {
  Reg r = cb_.reg(want);
  switch (f.kind) {
    case Folded::Int:
      if (want == TypeTable::kFloat)
        cb_.op(Opcode::MOVF).w(r).dbl(double(f.i));
      else
        cb_.emit(Opcode::MOVI, {r, std::uint32_t(std::int32_t(f.i))});
      break;
    case Folded::Float:
      cb_.op(Opcode::MOVF).w(r).dbl(f.f);
      break;
    case Folded::Bool:
      cb_.emit(Opcode::MOVB, {r, f.b ? 1u : 0u});
      break;
    case Folded::String:
      cb_.emit(Opcode::MOVS, {r, L_.string(f.s)});
      break;
    case Folded::Node:
      cb_.emit(Opcode::MOVN, {r, std::uint32_t(f.i)});
      break;
  }
  return r;
}

Reg ExprLowerer::valueAs(const Expr& e, TypeId want) {
  Reg r = value(e);
  if (cb_.typeOf(r) == want) return r;
  throw LowerError(e.loc, "internal error: expression of type '" + L_.prog.types.name(cb_.typeOf(r)) +
                              "' where '" + L_.prog.types.name(want) + "' is needed");
}

void ExprLowerer::into(const Expr& e, Reg dst) {
  Reg r = valueAs(e, cb_.typeOf(dst));
  if (r != dst) cb_.emit(Opcode::MOV, {dst, r});
}

Reg ExprLowerer::value(const Expr& e) {
  switch (e.kind) {
    case ExprKind::Var: {
      auto it = env.find(e.name);
      if (it == env.end()) throw LowerError(e.loc, "internal error: variable '" + e.name + "' is not bound");
      return it->second;
    }
    case ExprKind::Anon:
      throw LowerError(e.loc, "'_' has no value: it only matches anything in a body pattern (§5.2)");
    case ExprKind::Int: {
      Folded f;
      f.i = e.intValue;
      return folded(f, L_.typeOf(e));
    }
    case ExprKind::Float: {
      Folded f;
      f.kind = Folded::Float;
      f.f = floatLiteral(e);
      return folded(f, TypeTable::kFloat);
    }
    case ExprKind::Bool: {
      Folded f;
      f.kind = Folded::Bool;
      f.b = e.boolValue;
      return folded(f, TypeTable::kBool);
    }
    case ExprKind::String: {
      Folded f;
      f.kind = Folded::String;
      f.s = e.name;
      return folded(f, TypeTable::kString);
    }
    case ExprKind::Node: {
      Folded f;
      f.kind = Folded::Node;
      f.i = e.intValue;
      return folded(f, TypeTable::kNode);
    }
    case ExprKind::World:
    case ExprKind::Cpus:
    case ExprKind::Host:
    case ExprKind::Thread: {
      static const std::map<ExprKind, std::pair<Opcode, TypeId>> ops = {
          {ExprKind::World, {Opcode::WORLD, TypeTable::kInt}},
          {ExprKind::Cpus, {Opcode::CPUS, TypeTable::kInt}},
          {ExprKind::Host, {Opcode::HOST, TypeTable::kNode}},
          {ExprKind::Thread, {Opcode::THREAD, TypeTable::kThread}}};
      auto [op, type] = ops.at(e.kind);
      Reg r = cb_.reg(type);
      cb_.emit(op, {r});
      return r;
    }
    case ExprKind::Arg: {
      Reg r = cb_.reg(TypeTable::kString);
      cb_.emit(Opcode::ARG, {r, std::uint32_t(e.intValue)});
      L_.prog.highestArg = std::max(L_.prog.highestArg, std::uint32_t(e.intValue));
      return r;
    }
    case ExprKind::Const: {
      const Symbol key = e.sym;
      if (auto it = L_.folded.find(key); it != L_.folded.end()) return folded(it->second, L_.typeOf(e));
      if (auto it = L_.globals.find(key); it != L_.globals.end()) {
        Reg r = cb_.reg(L_.prog.globals.at(it->second).type);
        cb_.emit(Opcode::GLOBAL, {r, it->second});
        return r;
      }
      throw LowerError(e.loc, "constant '" + e.name + "' has no value (it depends on itself?)");
    }
    case ExprKind::Call:
      return call(e.sym, e.args, e.loc, L_.typeOf(e));
    case ExprKind::Convert: {
      if (std::optional<Reg> r = foldedArithmetic(e)) return *r;
      Reg a = valueAs(e.args.at(0), TypeTable::kInt);
      Reg r = cb_.reg(TypeTable::kFloat);
      cb_.emit(Opcode::I2F, {r, a});
      return r;
    }
    case ExprKind::Binary:
      if (e.op == BinOp::Append) return call(L_.ast.symbols.find("lappend"), e.args, e.loc, L_.typeOf(e));
      if (std::optional<Reg> r = foldedArithmetic(e)) return *r;
      return arithmetic(e);
    case ExprKind::Compare:
      if (!nilTest(e)) return compareValue(e);
      [[fallthrough]];
    case ExprKind::Not:
    case ExprKind::And:
    case ExprKind::Or: {
      Reg r = cb_.reg(TypeTable::kBool);
      Label done = cb_.label();
      cb_.emit(Opcode::MOVB, {r, 0});
      jumpIfFalse(e, done);
      cb_.emit(Opcode::MOVB, {r, 1});
      cb_.place(done);
      return r;
    }
    case ExprKind::In:  // X in L = lexists(L, X)
      return call(L_.ast.symbols.find("lexists"), std::vector<const Expr*>{&e.args.at(1), &e.args.at(0)},
                  e.loc, TypeTable::kBool);
    case ExprKind::Ins:  // L1 ins L2 = lexistss(L2, L1)
      return call(L_.ast.symbols.find("lexistss"), std::vector<const Expr*>{&e.args.at(1), &e.args.at(0)},
                  e.loc, TypeTable::kBool);
    case ExprKind::If: {
      Reg r = cb_.reg(L_.typeOf(e));
      Label otherwise = cb_.label(), done = cb_.label();
      jumpIfFalse(e.args.at(0), otherwise);
      into(e.args.at(1), r);
      cb_.op(Opcode::JMP).to(done);
      cb_.place(otherwise);
      into(e.args.at(2), r);
      cb_.place(done);
      return r;
    }
    case ExprKind::Let: {
      Reg v = value(e.args.at(0));
      auto saved = env.find(e.name) == env.end() ? std::optional<Reg>() : env[e.name];
      env[e.name] = v;
      Reg r = value(e.args.at(1));
      if (saved)
        env[e.name] = *saved;
      else
        env.erase(e.name);
      return r;
    }
    case ExprKind::Struct: {
      TypeId t = L_.typeOf(e);
      const auto span = L_.prog.types.fields(t);
      const std::vector<TypeId> types(span.begin(), span.end());  // interning below may move the pool
      std::vector<Reg> fields;
      for (size_t i = 0; i < e.args.size(); ++i) fields.push_back(valueAs(e.args[i], types.at(i)));
      Reg r = cb_.reg(t);
      cb_.op(Opcode::STRUCT).w(r).w(t).regs(fields);
      return r;
    }
    case ExprKind::List:
      return list(e);
  }
  throw LowerError(e.loc, "internal error: unknown expression");
}

Reg ExprLowerer::list(const Expr& e) {
  const TypeId t = L_.typeOf(e);
  const TypeId elem = L_.prog.types.element(t);
  size_t n = e.args.size();
  Reg tail;
  if (e.hasTail) {
    tail = valueAs(e.args.back(), t);
    --n;
  } else {
    tail = cb_.reg(t);
    cb_.emit(Opcode::NIL, {tail});
  }
  // Built from the back: [a, b | T] = CONS a (CONS b T).
  for (size_t i = n; i-- > 0;) {
    Reg head = valueAs(e.args[i], elem);
    Reg r = cb_.reg(t);
    cb_.emit(Opcode::CONS, {r, head, tail, t});
    tail = r;
  }
  return tail;
}

// Arithmetic on constants alone (`size - 1`, `damping / float(pages)`) becomes one move: the
// interpreter ran every operation of such an expression at each rule run (8queens' `!coord(A,
// size - 1, _)`: two moves and a subtraction before each test). foldConstant computes as the VM
// does (32-bit wrap-around, doubles, §5.5) and leaves a division by zero to the run-time error.
std::optional<Reg> ExprLowerer::foldedArithmetic(const Expr& e) {
  const std::optional<Folded> f = foldConstant(L_, e);
  if (!f) return std::nullopt;
  const TypeId t = L_.typeOf(e);
  if (!(f->kind == Folded::Float && t == TypeTable::kFloat) &&
      !(f->kind == Folded::Int && t == TypeTable::kInt))
    return std::nullopt;
  return folded(*f, t);
}

Reg ExprLowerer::arithmetic(const Expr& e) {
  const TypeId t = L_.typeOf(e);
  const bool isFloat = t == TypeTable::kFloat;
  if (!isFloat && t != TypeTable::kInt) throw LowerError(e.loc, "internal error: arithmetic on non-numbers");
  Opcode op = Opcode::ADDI;
  switch (e.op) {
    case BinOp::Add:
      op = isFloat ? Opcode::ADDF : Opcode::ADDI;
      break;
    case BinOp::Sub:
      op = isFloat ? Opcode::SUBF : Opcode::SUBI;
      break;
    case BinOp::Mul:
      op = isFloat ? Opcode::MULF : Opcode::MULI;
      break;
    case BinOp::Div:
      op = isFloat ? Opcode::DIVF : Opcode::DIVI;
      break;
    case BinOp::Mod:
      if (isFloat) throw LowerError(e.loc, "'%' takes int operands only (§5.5, §3.2)");
      op = Opcode::MODI;
      break;
    default:
      throw LowerError(e.loc, "internal error: unknown arithmetic operator");
  }
  Reg a = valueAs(e.args.at(0), t), b = valueAs(e.args.at(1), t);
  Reg r = cb_.reg(t);
  cb_.emit(op, {r, a, b});
  return r;
}

Reg ExprLowerer::compareValue(const Expr& e) {
  const Expr& lhs = e.args.at(0);
  const TypeId t = L_.typeOf(lhs);
  Reg a = valueAs(lhs, t), b = valueAs(e.args.at(1), t);
  Reg r = cb_.reg(TypeTable::kBool);
  if (e.op == BinOp::Eq || e.op == BinOp::Ne) {
    cb_.emit(e.op == BinOp::Eq ? Opcode::EQ : Opcode::NE, {r, a, b, t});
    return r;
  }
  const bool isFloat = t == TypeTable::kFloat;
  if (!isFloat && t != TypeTable::kInt)
    throw LowerError(e.loc, "'<', '<=', '>' and '>=' compare int or float values only (§3.2)");
  Opcode op = Opcode::LTI;
  switch (e.op) {
    case BinOp::Lt:
      op = isFloat ? Opcode::LTF : Opcode::LTI;
      break;
    case BinOp::Le:
      op = isFloat ? Opcode::LEF : Opcode::LEI;
      break;
    case BinOp::Gt:
      op = isFloat ? Opcode::GTF : Opcode::GTI;
      break;
    case BinOp::Ge:
      op = isFloat ? Opcode::GEF : Opcode::GEI;
      break;
    default:
      throw LowerError(e.loc, "internal error: unknown comparison");
  }
  cb_.emit(op, {r, a, b});
  return r;
}

void ExprLowerer::compareJump(const Expr& e, Label target, bool jumpWhen) {
  switch (e.kind) {
    case ExprKind::Not:
      compareJump(e.args.at(0), target, !jumpWhen);
      return;
    case ExprKind::And:
    case ExprKind::Or: {
      // Jump when (a && b) is false / (a || b) is true: either operand decides alone.
      const bool decidesAlone = (e.kind == ExprKind::And) != jumpWhen;
      if (decidesAlone) {
        compareJump(e.args.at(0), target, jumpWhen);
        compareJump(e.args.at(1), target, jumpWhen);
      } else {
        Label skip = cb_.label();
        compareJump(e.args.at(0), skip, !jumpWhen);
        compareJump(e.args.at(1), target, jumpWhen);
        cb_.place(skip);
      }
      return;
    }
    case ExprKind::Bool:
      if (e.boolValue == jumpWhen) cb_.op(Opcode::JMP).to(target);
      return;
    default:
      break;
  }
  if (const Expr* l = nilTest(e)) {
    Reg r = value(*l);
    const bool jumpIfNil = (e.op == BinOp::Eq) == jumpWhen;
    cb_.op(jumpIfNil ? Opcode::JNIL : Opcode::JNOTNIL).w(r).to(target);
    return;
  }
  Reg r = valueAs(e, TypeTable::kBool);
  cb_.op(jumpWhen ? Opcode::JT : Opcode::JF).w(r).to(target);
}

void ExprLowerer::jumpIfFalse(const Expr& cond, Label target) { compareJump(cond, target, false); }
void ExprLowerer::jumpIfTrue(const Expr& cond, Label target) { compareJump(cond, target, true); }

void ExprLowerer::testEqual(Reg r, const Expr& e, Label fail) {
  if (isEmptyList(e)) {
    cb_.op(Opcode::JNOTNIL).w(r).to(fail);
    return;
  }
  const TypeId t = cb_.typeOf(r);
  Reg v = valueAs(e, t);
  Reg b = cb_.reg(TypeTable::kBool);
  cb_.emit(Opcode::EQ, {b, r, v, t});
  cb_.op(Opcode::JF).w(b).to(fail);
}

Reg ExprLowerer::call(Symbol name, const std::vector<Expr>& args, SourceLoc loc, TypeId resultHint) {
  std::vector<const Expr*> ptrs;
  for (const Expr& a : args) ptrs.push_back(&a);
  return call(name, ptrs, loc, resultHint);
}

Reg ExprLowerer::call(Symbol name, const std::vector<const Expr*>& args, SourceLoc loc, TypeId resultHint) {
  std::vector<Reg> regs;
  for (const Expr* a : args) regs.push_back(value(*a));
  return callRegs(name, regs, loc, resultHint);
}

Reg ExprLowerer::callRegs(Symbol name, const std::vector<Reg>& regs, SourceLoc loc, TypeId resultHint) {
  const std::string& key = L_.ast.symbols.text(name);  // folded
  auto checkArgs = [&](const std::vector<TypeId>& params) {
    if (params.size() != regs.size()) throw LowerError(loc, "internal error: wrong argument count");
    for (size_t i = 0; i < regs.size(); ++i)
      if (cb_.typeOf(regs[i]) != params[i])
        throw LowerError(loc, "internal error: argument " + std::to_string(i + 1) + " of '" + key +
                                  "' has type '" + L_.prog.types.name(cb_.typeOf(regs[i])) + "'");
  };
  // User functions first, then built-ins, then externs (§5.5).
  if (auto it = L_.functions.find(name); it != L_.functions.end()) {
    const meldvm::Function& f = L_.prog.functions.at(it->second);
    checkArgs(f.params);
    Reg r = cb_.reg(f.result);
    cb_.op(Opcode::CALLF).w(r).w(it->second).regs(regs);
    return r;
  }
  bool known = false;
  for (const BuiltinFunction& b : builtinFunctions()) known |= b.name == key;
  if (known) {
    const meldvm::BuiltinInfo* b = meldvm::findBuiltin(std::string_view(key));
    if (!b)
      throw LowerError(loc,
                       "internal error: the built-in function '" + key + "' is missing from the VM's table");
    std::vector<TypeId> types;
    for (Reg r : regs) types.push_back(cb_.typeOf(r));
    // The VM resolves the polymorphic result the same way; no hidden type argument is passed.
    std::optional<TypeId> result = meldvm::resolveResult(L_.prog.types, *b, types);
    Reg r = cb_.reg(result ? *result : resultHint);
    cb_.op(Opcode::CALL).w(r).w(b->id).w(cb_.typeOf(r)).regs(regs);
    return r;
  }
  if (auto it = L_.externs.find(name); it != L_.externs.end()) {
    const meldvm::Extern& x = L_.prog.externs.at(it->second);
    checkArgs(x.params);
    Reg r = cb_.reg(x.result);
    cb_.op(Opcode::CALLX).w(r).w(it->second).regs(regs);
    return r;
  }
  throw LowerError(loc, "internal error: unknown function '" + key + "'");
}

}  // namespace meldc
