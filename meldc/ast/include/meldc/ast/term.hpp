// Items of rule bodies and heads (§5.2, §5.3): subgoals, constraints/assignments, exists,
// comprehensions, aggregate constructs and conditional heads.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meldc/ast/expr.hpp"
#include "meldc/source.hpp"

namespace meldc::ast {

enum class TermKind { Subgoal, Constraint, Exists, Comprehension, Aggregate, Conditional };

// Prefix of a subgoal: `!` persistent, `?` explicitly linear, `$` reused linear.
enum class Mark { None, Persistent, Linear, Reuse };

struct VarDecl {
  SourceLoc loc;
  std::string name;
};

enum class AggOp { Sum, Count, Collect, Min, Custom };

// `sum => V` or `custom f Start => V`.
struct AggSpec {
  SourceLoc loc;
  AggOp op = AggOp::Sum;
  std::string function;  // Custom: the folding function
  Symbol functionSym;
  Expr start;  // Custom: start value
  std::string var;
};

// Accepted aggregate shapes of §2.2 (letters as in the spec).
enum class AggShape { A, B, C, D, E, F, G };

struct Term {
  TermKind kind = TermKind::Subgoal;
  SourceLoc loc;

  // Subgoal: [mark] name(args) [@+Nms]
  Mark mark = Mark::None;
  std::string name;
  Symbol sym;  // the folded name
  SourceLoc nameLoc;
  std::vector<Expr> args;
  std::optional<int64_t> delayMs;

  // Constraint: the condition (or assignment `X = e`); Conditional: the `if` condition.
  Expr cond;

  // Exists / Comprehension / Aggregate: declared variables.
  std::vector<VarDecl> vars;
  // Aggregate only.
  std::vector<AggSpec> specs;
  AggShape shape = AggShape::A;

  // Exists: head = the parenthesised terms.
  // Comprehension: body, head.   Aggregate: body, perMatch (head0), head.
  // Conditional: head = then-branch, elseHead = otherwise-branch (empty for `1`).
  std::vector<Term> body;
  std::vector<Term> perMatch;
  std::vector<Term> head;
  std::vector<Term> elseHead;
};

}  // namespace meldc::ast
