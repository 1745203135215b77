// Expressions and conditions (§5.5). One plain struct with a kind tag; conditions (comparisons,
// `in`, `&&`, `||`, `~`) are expressions of boolean kind so `if` and constraints share them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meldc/ast/symbol.hpp"
#include "meldc/source.hpp"

namespace meldc::ast {

enum class ExprKind {
  Var,      // X                              name
  Anon,     // _
  Int,      // 3, -3                          intValue
  Float,    // 0.85                           floatValue, text
  Bool,     // true / false                   boolValue
  String,   // "text"                         name = the text between the quotes
  Node,     // @3                             intValue
  World,    // @world
  Cpus,     // @cpus
  Host,     // @host
  Thread,   // @thread
  Arg,      // @arg1                          intValue = 1
  Const,    // damping                        name
  Call,     // lnth(L, 0)                     name, args
  Convert,  // float(X)                       args[0]
  Binary,   // X + 1, L1 ++ L2                op, args[0..1]
  Compare,  // X < Y, X = 1                   op, args[0..1]
  In,       // X in L                         args[0..1]
  Ins,      // L1 ins L2                      args[0..1]
  Not,      // ~C                             args[0]
  And,      // C1 && C2                       args[0..1]
  Or,       // C1 || C2                       args[0..1]
  If,       // if C then A else B end         args = C, A, B
  Let,      // let X = V in B end             name = X, args = V, B
  Struct,   // :(1, 2.0, X)                   args
  List,     // [], nil, [1, 2], [H | T]       args = elements (+ tail when hasTail)
};

enum class BinOp { Add, Sub, Mul, Div, Mod, Append, Eq, Ne, Lt, Le, Gt, Ge };

struct Expr {
  ExprKind kind = ExprKind::Anon;
  SourceLoc loc;
  std::string name;
  Symbol sym;        // Const, Call: the folded name (internNames)
  std::string text;  // literal spelling of numbers
  int64_t intValue = 0;
  double floatValue = 0.0;
  bool boolValue = false;
  BinOp op = BinOp::Add;
  bool hasTail = false;     // List: the last element of args is the tail ([H | T])
  bool nilKeyword = false;  // List: written `nil`
  std::vector<Expr> args;
};

const char* binOpSpelling(BinOp op);

}  // namespace meldc::ast
