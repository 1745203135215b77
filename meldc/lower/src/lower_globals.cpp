// Constants (§4.6) and functions (§4.7): constants computable at compile time are folded (float
// literals in single precision, §1.4; @world = the number of initial nodes); the others become
// globals computed once by Program::globalsInit. Each `fun` becomes a code block with its
// parameters in registers 0..n-1 and its result in register n.
#include <cmath>
#include <set>

#include "code_builder.hpp"
#include "lower_expr.hpp"

namespace meldc {

using namespace meldc::ast;
using meldvm::Opcode;

namespace {

std::optional<Folded> foldArithmetic(BinOp op, const Folded& a, const Folded& b) {
  const bool numeric = (a.kind == Folded::Int || a.kind == Folded::Float) &&
                       (b.kind == Folded::Int || b.kind == Folded::Float);
  if (!numeric) return std::nullopt;
  Folded r;
  if (a.kind == Folded::Float || b.kind == Folded::Float) {
    const double x = a.kind == Folded::Float ? a.f : double(a.i),
                 y = b.kind == Folded::Float ? b.f : double(b.i);
    r.kind = Folded::Float;
    switch (op) {
      case BinOp::Add:
        r.f = x + y;
        return r;
      case BinOp::Sub:
        r.f = x - y;
        return r;
      case BinOp::Mul:
        r.f = x * y;
        return r;
      case BinOp::Div:
        r.f = x / y;
        return r;
      default:
        return std::nullopt;
    }
  }
  // 32-bit wrap-around like the VM (§5.5).
  const auto x = std::int32_t(a.i), y = std::int32_t(b.i);
  const auto wrap = [](std::int64_t v) {
    return std::int64_t(std::int32_t(std::uint32_t(std::uint64_t(v))));
  };
  switch (op) {
    case BinOp::Add:
      r.i = wrap(std::int64_t(x) + y);
      return r;
    case BinOp::Sub:
      r.i = wrap(std::int64_t(x) - y);
      return r;
    case BinOp::Mul:
      r.i = wrap(std::int64_t(x) * y);
      return r;
    case BinOp::Div:
    case BinOp::Mod:
      if (y == 0 || (x == INT32_MIN && y == -1)) return std::nullopt;  // left to the run-time error
      r.i = op == BinOp::Div ? x / y : x % y;
      return r;
    default:
      return std::nullopt;
  }
}

}  // namespace

std::optional<Folded> foldConstant(Lowering& L, const Expr& e) {
  Folded f;
  switch (e.kind) {
    case ExprKind::Int: {
      const TypeExpr* t = L.typing.of(e);
      if (t && t->kind == TypeKind::Float) {
        f.kind = Folded::Float;
        f.f = double(e.intValue);
      } else {
        f.i = e.intValue;
      }
      return f;
    }
    case ExprKind::Float:
      f.kind = Folded::Float;
      f.f = floatLiteral(e);
      return f;
    case ExprKind::Bool:
      f.kind = Folded::Bool;
      f.b = e.boolValue;
      return f;
    case ExprKind::String:
      f.kind = Folded::String;
      f.s = e.name;
      return f;
    case ExprKind::Node:
      f.kind = Folded::Node;
      f.i = e.intValue;
      return f;
    case ExprKind::World:
      f.i = std::int64_t(L.prog.nodeSourceIds.size());
      return f;
    case ExprKind::Const: {
      auto it = L.folded.find(e.sym);
      if (it == L.folded.end()) return std::nullopt;
      return it->second;
    }
    case ExprKind::Convert: {
      std::optional<Folded> a = foldConstant(L, e.args.at(0));
      if (!a || a->kind != Folded::Int) return std::nullopt;
      f.kind = Folded::Float;
      f.f = double(a->i);
      return f;
    }
    case ExprKind::Binary: {
      std::optional<Folded> a = foldConstant(L, e.args.at(0)), b = foldConstant(L, e.args.at(1));
      if (!a || !b) return std::nullopt;
      return foldArithmetic(e.op, *a, *b);
    }
    default:
      return std::nullopt;
  }
}

void lowerConstantsAndFunctions(Lowering& L) {
  // Functions: all signatures first (calls may come before the callee, or be recursive).
  for (const FunDecl& f : L.ast.funs) {
    meldvm::Function fn;
    fn.name = f.name;
    for (const FunParam& p : f.params) fn.params.push_back(L.vmType(p.type));
    fn.result = L.vmType(f.result);
    L.functions[f.sym] = std::uint32_t(L.prog.functions.size());
    L.prog.functions.push_back(std::move(fn));
  }
  // Constants in program order: a constant folds when everything it uses folded before it.
  CodeBuilder init;
  ExprLowerer ex(L, init);
  for (const ConstDecl& c : L.ast.consts) {
    const Symbol key = c.sym;
    try {
      if (std::optional<Folded> f = foldConstant(L, c.value)) {
        L.folded[key] = *f;
        continue;
      }
      auto t = L.typing.consts.find(key);
      if (t == L.typing.consts.end()) throw LowerError(c.loc, "internal error: constant without a type");
      const auto id = std::uint32_t(L.prog.globals.size());
      L.prog.globals.push_back(meldvm::Global{c.name, L.vmType(t->second)});
      Reg r = ex.valueAs(c.value, L.prog.globals.back().type);
      init.emit(Opcode::SETGLOBAL, {id, r});
      L.globals[key] = id;
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
  }
  init.op(Opcode::RET);
  L.prog.globalsInit = init.finish("constants");

  for (size_t i = 0; i < L.ast.funs.size(); ++i) {
    const FunDecl& f = L.ast.funs[i];
    meldvm::Function& fn = L.prog.functions[i];
    try {
      CodeBuilder cb;
      ExprLowerer body(L, cb);
      for (size_t p = 0; p < f.params.size(); ++p) body.env[f.params[p].name] = cb.reg(fn.params[p]);
      Reg result = cb.reg(fn.result);
      body.into(f.body, result);
      cb.op(Opcode::RET);
      fn.block = cb.finish("fun " + f.name);
    } catch (const LowerError& e) {
      L.diag.error(e.loc, e.what());
    }
  }
}

}  // namespace meldc
