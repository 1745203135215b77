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
  groundFacts.append(std::move(other.groundFacts), static_cast<std::uint32_t>(rules.size()));
  moveAppend(rules, other.rules);
}

void GroundFacts::append(GroundFacts&& other, std::uint32_t rulesBefore) {
  std::vector<std::uint32_t> nameIds;
  for (const std::string& n : other.names) {
    std::uint32_t id = 0;
    while (id < names.size() && names[id] != n) ++id;  // a handful of names per program
    if (id == names.size()) names.push_back(n);
    nameIds.push_back(id);
  }
  const auto argsBefore = static_cast<std::uint32_t>(args.size());
  for (GroundFact f : other.facts) {
    f.name = nameIds[f.name];
    f.firstArg += argsBefore;
    f.position += rulesBefore;
    facts.push_back(f);
  }
  args.insert(args.end(), other.args.begin(), other.args.end());
  other = GroundFacts{};
}

}  // namespace meldc::ast
