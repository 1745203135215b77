// Declarations and directives (§4): node subtypes, type aliases, predicates (also imported ones),
// exports, directives, externs, constants and functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meldc/ast/expr.hpp"
#include "meldc/ast/type.hpp"
#include "meldc/source.hpp"

namespace meldc::ast {

struct NodeTypeDecl {  // node page.
  SourceLoc loc;
  std::string name;
  Symbol sym;
};

struct TypeAliasDecl {  // type int number.
  SourceLoc loc;
  std::string name;
  TypeExpr type;
  Symbol sym;
};

enum class FieldAgg { None, Min, Max, Sum, First };

struct FieldDecl {
  SourceLoc loc;
  FieldAgg agg = FieldAgg::None;
  TypeExpr type;
  std::string argName;  // `int Key`: a comment only
};

// type [linear] [route] [action] name(fields).   or   import ... name(fields) as alias from lib.
struct PredicateDecl {
  SourceLoc loc;
  std::string name;
  Symbol sym;
  SourceLoc nameLoc;
  bool linear = false;
  bool route = false;
  bool action = false;
  std::vector<FieldDecl> fields;  // including the home argument
  bool imported = false;
  std::string importedName;  // import: the name in the library (the predicate is called `name`)
  std::string importedFrom;
  // Made by localization (§6.7): `___` + reversed route name (reverseRoute) or `__mangledname<k>`.
  bool reverseRoute = false;
  bool generated = false;
};

struct ExportDecl {
  SourceLoc loc;
  std::string name;
};

enum class DirectiveKind { Index, Compact, Data, Allocator, Priority };

enum class PriorityKind {
  Static,
  ClusterStatic,
  ClusterRandom,
  NoInitial,
  Initial,
  Default,
  NoPriority,
  OrderAsc,
  OrderDesc,
  Lower,   // priority a < b.
  Higher,  // priority a > b.
};

struct Directive {
  SourceLoc loc;
  DirectiveKind kind = DirectiveKind::Index;
  std::string name;  // Index/Compact/Data: predicate or template; Priority a<b: a
  Symbol sym;
  SourceLoc nameLoc;
  int64_t position = 0;               // Index: 1-based field counting the home argument
  std::string text;                   // Data: file; Allocator: allocator name
  std::vector<std::string> dataArgs;  // Data: ["a" "b"]
  PriorityKind priority = PriorityKind::Static;
  double value = 0.0;  // @initial / @default / @no_priority
  std::string other;   // Priority a<b: b
  Symbol otherSym;
  SourceLoc otherLoc;
};

struct ExternDecl {  // extern int myfun(int, float).
  SourceLoc loc;
  std::string name;
  Symbol sym;
  TypeExpr result;
  std::vector<FieldDecl> params;
};

struct ConstDecl {  // const name = expr.
  SourceLoc loc;
  std::string name;
  Symbol sym;
  Expr value;
  bool fromCommandLine = false;  // -DNAME=VALUE
};

struct FunParam {
  SourceLoc loc;
  TypeExpr type;
  std::string name;
};

struct FunDecl {  // fun name(int X, ...) : type = expr.
  SourceLoc loc;
  std::string name;
  Symbol sym;
  std::vector<FunParam> params;
  TypeExpr result;
  Expr body;
};

}  // namespace meldc::ast
