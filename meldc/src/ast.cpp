// Small helpers of the AST structs.
#include "meldc/ast/expr.hpp"
#include "meldc/ast/program.hpp"

namespace meldc::ast {

const char* binOpSpelling(BinOp op) {
  switch (op) {
    case BinOp::Add:
      return "+";
    case BinOp::Sub:
      return "-";
    case BinOp::Mul:
      return "*";
    case BinOp::Div:
      return "/";
    case BinOp::Mod:
      return "%";
    case BinOp::Append:
      return "++";
    case BinOp::Eq:
      return "=";
    case BinOp::Ne:
      return "<>";
    case BinOp::Lt:
      return "<";
    case BinOp::Le:
      return "<=";
    case BinOp::Gt:
      return ">";
    case BinOp::Ge:
      return ">=";
  }
  return "?";
}

template <class T>
static void moveAppend(std::vector<T>& to, std::vector<T>& from) {
  for (T& x : from) to.push_back(std::move(x));
  from.clear();
}

void Program::append(Program&& other) {
  moveAppend(includes, other.includes);
  moveAppend(nodeTypes, other.nodeTypes);
  moveAppend(typeAliases, other.typeAliases);
  moveAppend(predicates, other.predicates);
  moveAppend(exports, other.exports);
  moveAppend(directives, other.directives);
  moveAppend(externs, other.externs);
  moveAppend(consts, other.consts);
  moveAppend(funs, other.funs);
  moveAppend(rules, other.rules);
}

}  // namespace meldc::ast
