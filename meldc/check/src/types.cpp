#include "meldc/types.hpp"

#include <cctype>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "meldc/builtins.hpp"
#include "meldc/case_folding.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

// Types are nodes of a union-find forest; a Var is unknown (Num: an integer literal, int or float).
enum class K { Var, Num, Int, Float, Bool, String, Node, Thread, List, Set, Array, Struct, AnyStruct };

struct TypeNode {
  K kind = K::Var;
  int parent = -1;
  std::vector<int> args;
};

struct Signature {
  std::vector<int> params;
  int result = -1;
};

class Checker {
 public:
  Checker(const Program& p, Diagnostics& diag, Typing* out = nullptr) : p_(p), diag_(diag), out_(out) {}

  void run() {
    for (const TypeAliasDecl& a : p_.typeAliases) aliases_[a.sym] = &a.type;
    for (const PredicateDecl& d : p_.predicates) preds_[d.sym] = &d;
    for (const FunDecl& f : p_.funs) funs_[f.sym] = &f;
    for (const ExternDecl& e : p_.externs) externs_[e.sym] = &e;
    for (const ConstDecl& c : p_.consts) constDecls_[c.sym] = &c;
    for (const ConstDecl& c : p_.consts) constType(c);
    for (const FunDecl& f : p_.funs) fun(f);
    for (const Rule& r : p_.rules) rule(r);
    if (out_) record();
  }

 private:
  // --- the type store ------------------------------------------------------------------------

  int make(K kind, std::vector<int> args = {}) {
    types_.push_back(TypeNode{kind, -1, std::move(args)});
    return static_cast<int>(types_.size()) - 1;
  }
  int fresh() { return make(K::Var); }

  int find(int t) {
    while (types_[static_cast<size_t>(t)].parent >= 0) t = types_[static_cast<size_t>(t)].parent;
    return t;
  }
  TypeNode& node(int t) { return types_[static_cast<size_t>(find(t))]; }

  bool occurs(int var, int t) {
    t = find(t);
    if (t == var) return true;
    for (int a : types_[static_cast<size_t>(t)].args)
      if (occurs(var, a)) return true;
    return false;
  }

  bool unify(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return true;
    TypeNode& x = types_[static_cast<size_t>(a)];
    TypeNode& y = types_[static_cast<size_t>(b)];
    if (x.kind == K::Var) {
      if (occurs(a, b)) return false;
      x.parent = b;
      return true;
    }
    if (y.kind == K::Var) return unify(b, a);
    if (x.kind == K::Num) {
      if (y.kind != K::Num && y.kind != K::Int && y.kind != K::Float) return false;
      x.parent = b;
      return true;
    }
    if (y.kind == K::Num) return unify(b, a);
    // AnyStruct is the argument of the *struct built-ins (§5.6): a struct of floats. Its fields
    // become float (an int literal adapts, an int variable is a mismatch).
    if (x.kind == K::AnyStruct && y.kind == K::AnyStruct) {
      x.parent = b;
      return true;
    }
    if (x.kind == K::AnyStruct && y.kind == K::Struct) {
      const std::vector<int> fields = y.args;  // a copy: make() may grow the store
      for (int f : fields) {  // checked first: a failed unification must leave both types as they were
        const K k = node(f).kind;
        if (k != K::Var && k != K::Num && k != K::Float) return false;
      }
      types_[static_cast<size_t>(a)].parent = b;
      for (int f : fields)
        if (!unify(f, make(K::Float))) return false;
      return true;
    }
    if (y.kind == K::AnyStruct && x.kind == K::Struct) return unify(b, a);
    if (x.kind != y.kind || x.args.size() != y.args.size()) return false;
    std::vector<int> xa = x.args, ya = y.args;  // copies: unify may grow the store
    for (size_t i = 0; i < xa.size(); ++i)
      if (!unify(xa[i], ya[i])) return false;
    return true;
  }

  std::string text(int t) {
    TypeNode n = node(t);
    switch (n.kind) {
      case K::Var:
        return "any";
      case K::Num:
        return "int";
      case K::Int:
        return "int";
      case K::Float:
        return "float";
      case K::Bool:
        return "bool";
      case K::String:
        return "string";
      case K::Node:
        return "node";
      case K::Thread:
        return "thread";
      case K::List:
        return "list " + text(n.args[0]);
      case K::Set:
        return "set " + text(n.args[0]);
      case K::Array:
        return "array " + text(n.args[0]);
      case K::AnyStruct:
        return "struct of floats";
      case K::Struct: {
        std::string s = ":(";
        for (size_t i = 0; i < n.args.size(); ++i) s += (i ? ", " : "") + text(n.args[i]);
        return s + ")";
      }
    }
    return "?";
  }

  K kindOf(int t) { return node(t).kind; }
  bool isNumeric(int t) {
    K k = kindOf(t);
    return k == K::Num || k == K::Int || k == K::Float;
  }

  // Declared types (aliases followed, node subtypes are nodes).
  int fromDecl(const TypeExpr& t, int depth = 0) {
    switch (t.kind) {
      case TypeKind::Int:
        return make(K::Int);
      case TypeKind::Float:
        return make(K::Float);
      case TypeKind::Bool:
        return make(K::Bool);
      case TypeKind::String:
        return make(K::String);
      case TypeKind::Node:
        return make(K::Node);
      case TypeKind::Thread:
        return make(K::Thread);
      case TypeKind::Named: {
        auto it = aliases_.find(t.sym);
        if (it == aliases_.end() || depth > 64) return make(K::Node);  // a node subtype
        return fromDecl(*it->second, depth + 1);
      }
      case TypeKind::List:
        return make(K::List, {fromDecl(t.args.at(0), depth)});
      case TypeKind::Set:
        return make(K::Set, {fromDecl(t.args.at(0), depth)});
      case TypeKind::Array:
        return make(K::Array, {fromDecl(t.args.at(0), depth)});
      case TypeKind::Struct: {
        std::vector<int> args;
        for (const TypeExpr& a : t.args) args.push_back(fromDecl(a, depth));
        return make(K::Struct, std::move(args));
      }
    }
    return fresh();
  }

  int parseSig(std::string_view& s, int elem) {
    char c = s.front();
    s.remove_prefix(1);
    switch (c) {
      case 'i':
        return make(K::Int);
      case 'f':
        return make(K::Float);
      case 'b':
        return make(K::Bool);
      case 's':
        return make(K::String);
      case 'n':
        return make(K::Node);
      case 't':
        return make(K::Thread);
      case 'T':
        return elem;
      case 'R':  // a struct of floats (builtins.def)
      case 'Q':
        return make(K::AnyStruct);
      case 'L':
        return make(K::List, {parseSig(s, elem)});
      case 'A':
        return make(K::Array, {parseSig(s, elem)});
      case 'S':
        return make(K::Set, {parseSig(s, elem)});
      default:
        return fresh();
    }
  }

  Signature signature(std::string_view spec) {
    Signature sig;
    int elem = fresh();
    while (!spec.empty()) {
      if (spec.front() == ',') {
        spec.remove_prefix(1);
        continue;
      }
      if (spec.front() == '>') {
        spec.remove_prefix(1);
        sig.result = parseSig(spec, elem);
        break;
      }
      sig.params.push_back(parseSig(spec, elem));
    }
    return sig;
  }

  // The signature of a function call: user function, built-in, extern (§5.5); nullopt if unknown.
  std::optional<Signature> functionSignature(Symbol name) {
    if (auto it = funs_.find(name); it != funs_.end()) {
      Signature sig;
      for (const FunParam& param : it->second->params) sig.params.push_back(fromDecl(param.type));
      sig.result = fromDecl(it->second->result);
      return sig;
    }
    if (const BuiltinFunction* b = findBuiltinFunction(p_.symbols.text(name))) return signature(b->signature);
    if (auto it = externs_.find(name); it != externs_.end()) {
      Signature sig;
      for (const FieldDecl& f : it->second->params) sig.params.push_back(fromDecl(f.type));
      sig.result = fromDecl(it->second->result);
      return sig;
    }
    return std::nullopt;
  }

  // Field types of a predicate; nullopt if unknown (instruction or undeclared).
  std::optional<std::vector<int>> predicateFields(Symbol name) {
    if (auto it = preds_.find(name); it != preds_.end()) {
      std::vector<int> fields;
      for (const FieldDecl& f : it->second->fields) fields.push_back(fromDecl(f.type));
      return fields;
    }
    if (const BuiltinPredicate* b = findBuiltinPredicate(p_.symbols.text(name)))
      return signature(b->fields).params;
    return std::nullopt;
  }

  // --- diagnostics ---------------------------------------------------------------------------

  // Unifies the type of `e` with `expected`, reporting a mismatch at `e`.
  void expect(const Expr& e, int actual, int expected, const std::string& where) {
    if (unify(actual, expected)) return;
    std::string what =
        e.kind == ExprKind::Var ? "variable '" + e.name + "' has type '" : "expression has type '";
    diag_.error(e.loc, "type mismatch: " + what + text(actual) + "' but " + where + " expects '" +
                           text(expected) + "'");
  }

  // --- expressions ---------------------------------------------------------------------------

  using Scope = std::map<std::string, int>;

  int var(const std::string& name, Scope& scope) {
    auto it = scope.find(name);
    if (it != scope.end()) return it->second;
    int t = fresh();
    scope[name] = t;
    return t;
  }

  int constType(const ConstDecl& c) {
    if (auto it = constTypes_.find(c.sym); it != constTypes_.end()) return it->second;
    int t = fresh();
    constTypes_[c.sym] = t;  // a cycle sees an unknown type
    Scope scope;
    int v = expr(c.value, scope);
    if (!unify(t, v)) diag_.error(c.value.loc, "constant '" + c.name + "' has conflicting types");
    if (kindOf(t) == K::Num) unify(t, make(K::Int));  // int when both are possible (§3.2)
    return t;
  }

  void requireNumeric(const Expr& e, int t, const std::string& what) {
    if (isNumeric(t) || kindOf(t) == K::Var) {
      if (kindOf(t) == K::Var) node(t).kind = K::Num;
      return;
    }
    diag_.error(e.loc, what + " needs int or float operands, not '" + text(t) + "'");
  }

  int condition(const Expr& e, Scope& scope, const std::string& where) {
    int t = expr(e, scope);
    if (!unify(t, make(K::Bool))) diag_.error(e.loc, where + " must be a bool, not '" + text(t) + "'");
    return t;
  }

  void call(const Expr& e, const std::vector<Expr>& args, const std::string& name, Symbol sym, Scope& scope,
            int& result) {
    std::optional<Signature> sig = functionSignature(sym);
    std::vector<int> argTypes;
    for (const Expr& a : args) argTypes.push_back(expr(a, scope));
    if (!sig || sig->params.size() != args.size()) {
      result = fresh();
      return;
    }
    for (size_t i = 0; i < args.size(); ++i)
      expect(args[i], argTypes[i], sig->params[i],
             "argument " + std::to_string(i + 1) + " of function '" + name + "'");
    result = sig->result >= 0 ? sig->result : fresh();
    (void)e;
  }

  bool isEmptyList(const Expr& e) { return e.kind == ExprKind::List && e.args.empty(); }

  int expr(const Expr& e, Scope& scope) {
    int t = exprType(e, scope);
    if (out_) exprTypes_[&e] = t;
    return t;
  }

  int exprType(const Expr& e, Scope& scope) {
    switch (e.kind) {
      case ExprKind::Var:
        return var(e.name, scope);
      case ExprKind::Anon:
        return fresh();
      case ExprKind::Int:
        return make(K::Num);
      case ExprKind::Float:
        return make(K::Float);
      case ExprKind::Bool:
        return make(K::Bool);
      case ExprKind::String:
      case ExprKind::Arg:
        return make(K::String);
      case ExprKind::Node:
      case ExprKind::Host:
        return make(K::Node);
      case ExprKind::World:
      case ExprKind::Cpus:
        return make(K::Int);
      case ExprKind::Thread:
        return make(K::Thread);
      case ExprKind::Const: {
        auto it = constDecls_.find(e.sym);
        return it == constDecls_.end() ? fresh() : constType(*it->second);
      }
      case ExprKind::Call: {
        int result = -1;
        call(e, e.args, e.name, e.sym, scope, result);
        return result;
      }
      case ExprKind::Convert: {
        int a = expr(e.args.at(0), scope);
        expect(e.args[0], a, make(K::Int), "float()");
        return make(K::Float);
      }
      case ExprKind::Binary: {
        int a = expr(e.args.at(0), scope), b = expr(e.args.at(1), scope);
        if (e.op == BinOp::Append) {
          int list = make(K::List, {fresh()});
          expect(e.args[0], a, list, "'++'");
          expect(e.args[1], b, list, "'++'");
          return list;
        }
        std::string op = std::string("'") + binOpSpelling(e.op) + "'";
        if (e.op == BinOp::Mod) {
          bool ok = unify(a, make(K::Int)) && unify(b, make(K::Int));
          if (!ok)
            diag_.error(e.loc, "'%' works on int only, not on '" + text(kindOf(a) == K::Int ? b : a) + "'");
          return ok ? a : fresh();
        }
        if (!unify(a, b)) {
          diag_.error(e.loc, "operands of " + op + " have different types: '" + text(a) + "' and '" +
                                 text(b) + "' (use float() to convert an int)");
          return fresh();
        }
        requireNumeric(e, a, op);
        return a;
      }
      case ExprKind::Compare:
        compare(e, scope);
        return make(K::Bool);
      case ExprKind::In: {
        int x = expr(e.args.at(0), scope), l = expr(e.args.at(1), scope);
        expect(e.args[1], l, make(K::List, {x}), "'in'");
        return make(K::Bool);
      }
      case ExprKind::Ins: {
        int a = expr(e.args.at(0), scope), b = expr(e.args.at(1), scope);
        int list = make(K::List, {fresh()});
        expect(e.args[0], a, list, "'ins'");
        expect(e.args[1], b, list, "'ins'");
        return make(K::Bool);
      }
      case ExprKind::Not:
        condition(e.args.at(0), scope, "the operand of '~'");
        return make(K::Bool);
      case ExprKind::And:
      case ExprKind::Or: {
        const char* op = e.kind == ExprKind::And ? "'&&'" : "'||'";
        condition(e.args.at(0), scope, std::string("the left operand of ") + op);
        condition(e.args.at(1), scope, std::string("the right operand of ") + op);
        return make(K::Bool);
      }
      case ExprKind::If: {
        condition(e.args.at(0), scope, "the condition of 'if'");
        int a = expr(e.args.at(1), scope), b = expr(e.args.at(2), scope);
        if (!unify(a, b)) {
          diag_.error(e.loc,
                      "the branches of 'if' have different types: '" + text(a) + "' and '" + text(b) + "'");
          return fresh();
        }
        return a;
      }
      case ExprKind::Let: {
        int v = expr(e.args.at(0), scope);
        auto saved = scope.find(e.name) == scope.end() ? std::optional<int>() : scope[e.name];
        scope[e.name] = v;
        int body = expr(e.args.at(1), scope);
        if (saved)
          scope[e.name] = *saved;
        else
          scope.erase(e.name);
        return body;
      }
      case ExprKind::Struct: {
        std::vector<int> args;
        for (const Expr& a : e.args) args.push_back(expr(a, scope));
        return make(K::Struct, std::move(args));
      }
      case ExprKind::List: {
        int elem = fresh();
        int list = make(K::List, {elem});
        size_t n = e.args.size() - (e.hasTail ? 1 : 0);
        for (size_t i = 0; i < n; ++i) expect(e.args[i], expr(e.args[i], scope), elem, "a list element");
        if (e.hasTail) expect(e.args.back(), expr(e.args.back(), scope), list, "the tail of a list");
        return list;
      }
    }
    return fresh();
  }

  void compare(const Expr& e, Scope& scope) {
    const Expr& l = e.args.at(0);
    const Expr& r = e.args.at(1);
    int a = expr(l, scope), b = expr(r, scope);
    std::string op = std::string("'") + binOpSpelling(e.op) + "'";
    if (!unify(a, b)) {
      diag_.error(e.loc, "cannot compare '" + text(a) + "' with '" + text(b) + "' using " + op +
                             (isNumeric(a) && isNumeric(b) ? " (use float() to convert an int)" : ""));
      return;
    }
    K k = kindOf(a);
    if (e.op == BinOp::Eq || e.op == BinOp::Ne) {
      if (k == K::List && (isEmptyList(l) || isEmptyList(r))) return;  // nil test
      // `X = expr` with X unbound is an assignment: any type.
      if (e.op == BinOp::Eq && (l.kind == ExprKind::Var || r.kind == ExprKind::Var)) return;
      bool ok = k == K::Var || k == K::Num || k == K::Int || k == K::Float || k == K::Node ||
                k == K::Thread || (k == K::Bool && e.op == BinOp::Eq);
      if (!ok) diag_.error(e.loc, "values of type '" + text(a) + "' cannot be compared with " + op);
      return;
    }
    if (kindOf(a) == K::Var) node(a).kind = K::Num;
    if (!isNumeric(a)) diag_.error(e.loc, op + " compares int or float values, not '" + text(a) + "'");
  }

  // --- functions, rules ----------------------------------------------------------------------

  void fun(const FunDecl& f) {
    Scope scope;
    for (const FunParam& param : f.params) scope[param.name] = fromDecl(param.type);
    int body = expr(f.body, scope);
    expect(f.body, body, fromDecl(f.result), "the result of function '" + f.name + "'");
  }

  void subgoal(const Term& t, Scope& scope, bool inBody) {
    std::optional<std::vector<int>> fields = predicateFields(t.sym);
    if (!fields) {
      // A body subgoal that is a function call: a boolean constraint.
      if (inBody && functionSignature(t.sym)) {
        int result = -1;
        Expr dummy;
        dummy.loc = t.loc;
        call(dummy, t.args, t.name, t.sym, scope, result);
        if (!unify(result, make(K::Bool)))
          diag_.error(t.loc,
                      "a condition must be a bool, but '" + t.name + "' returns '" + text(result) + "'");
        return;
      }
      for (const Expr& a : t.args) expr(a, scope);
      return;
    }
    for (size_t i = 0; i < t.args.size(); ++i) {
      int a = expr(t.args[i], scope);
      if (i < fields->size())
        expect(t.args[i], a, (*fields)[i],
               i == 0 ? "the home argument of '" + t.name + "'"
                      : "argument " + std::to_string(i + 1) + " of '" + t.name + "'");
    }
  }

  void terms(const std::vector<Term>& ts, Scope& scope, bool inBody) {
    for (const Term& t : ts) term(t, scope, inBody);
  }

  void term(const Term& t, Scope& scope, bool inBody) {
    switch (t.kind) {
      case TermKind::Subgoal:
        subgoal(t, scope, inBody);
        break;
      case TermKind::Constraint:
        condition(t.cond, scope, "a condition");
        break;
      case TermKind::Exists:
        for (const VarDecl& v : t.vars)
          if (!unify(var(v.name, scope), make(K::Node)))
            diag_.error(v.loc, "variable '" + v.name + "' of 'exists' is a node, not '" +
                                   text(var(v.name, scope)) + "'");
        terms(t.head, scope, false);
        break;
      case TermKind::Comprehension: {
        // The variables first bound inside are its own (§5.3.3): another comprehension or
        // aggregate of the head may use the same names for values of other types.
        Scope inner = scope;
        terms(t.body, inner, true);
        terms(t.head, inner, false);
        break;
      }
      case TermKind::Aggregate: {
        Scope inner = scope;
        aggregate(t, inner);
        break;
      }
      case TermKind::Conditional:
        condition(t.cond, scope, "the condition of 'if'");
        terms(t.head, scope, false);
        terms(t.elseHead, scope, false);
        break;
    }
  }

  void aggregate(const Term& t, Scope& scope) {
    // Inside Body/Head0 a spec variable is one value; in Head it is the aggregated value.
    std::vector<std::pair<const AggSpec*, int>> items;
    for (const AggSpec& s : t.specs) {
      if (s.op == AggOp::Count) {  // not bound in the body
        if (out_) aggItemTypes_[&s] = make(K::Int);
        continue;
      }
      items.emplace_back(&s, var(s.var, scope));
      if (out_) aggItemTypes_[&s] = items.back().second;
    }
    terms(t.body, scope, true);
    terms(t.perMatch, scope, false);
    for (const AggSpec& s : t.specs) {
      int item = -1;
      for (auto& [spec, ty] : items)
        if (spec == &s) item = ty;
      int result = -1;
      switch (s.op) {
        case AggOp::Count:
          result = make(K::Int);
          break;
        case AggOp::Collect:
          result = make(K::List, {item});
          break;
        case AggOp::Sum:
          if (kindOf(item) == K::Var) node(item).kind = K::Num;
          if (!isNumeric(item))
            diag_.error(s.loc, "'sum' adds int or float values, but '" + s.var + "' is '" + text(item) + "'");
          result = item;
          break;
        case AggOp::Min:
          if (!unify(item, make(K::Int)))
            diag_.error(s.loc,
                        "'min' aggregates int values only, but '" + s.var + "' is '" + text(item) + "'");
          result = item;
          break;
        case AggOp::Custom: {
          std::optional<Signature> sig = functionSignature(s.functionSym);
          int start = expr(s.start, scope);
          if (sig && sig->params.size() == 2) {
            if (!unify(sig->params[0], item) || !unify(sig->params[1], item) || !unify(sig->result, item))
              diag_.error(s.loc, "custom aggregate function '" + s.function +
                                     "' must take two values of the type of '" + s.var + "' and return it");
            expect(s.start, start, item, "the start value of the custom aggregate");
          }
          result = item;
          break;
        }
      }
      scope[s.var] = result;
    }
    terms(t.head, scope, false);
  }

  void rule(const Rule& r) {
    Scope scope;
    terms(r.body, scope, true);
    terms(r.head, scope, false);
  }

  // --- recording (inferTypes) ----------------------------------------------------------------

  TypeExpr resolved(int t, int depth = 0) {
    TypeExpr out;
    const TypeNode n = node(t);
    auto elem = [&](TypeKind kind) {
      out.kind = kind;
      out.args.push_back(n.args.empty() || depth > 32 ? TypeExpr{} : resolved(n.args[0], depth + 1));
    };
    switch (n.kind) {
      case K::Var:
      case K::Num:
      case K::Int:
      case K::AnyStruct:  // only reachable through unused polymorphic results
        out.kind = TypeKind::Int;
        break;
      case K::Float:
        out.kind = TypeKind::Float;
        break;
      case K::Bool:
        out.kind = TypeKind::Bool;
        break;
      case K::String:
        out.kind = TypeKind::String;
        break;
      case K::Node:
        out.kind = TypeKind::Node;
        break;
      case K::Thread:
        out.kind = TypeKind::Thread;
        break;
      case K::List:
        elem(TypeKind::List);
        break;
      case K::Set:
        elem(TypeKind::Set);
        break;
      case K::Array:
        elem(TypeKind::Array);
        break;
      case K::Struct:
        out.kind = TypeKind::Struct;
        for (int a : n.args) out.args.push_back(depth > 32 ? TypeExpr{} : resolved(a, depth + 1));
        break;
    }
    return out;
  }

  void record() {
    for (const auto& [e, t] : exprTypes_) out_->exprs[e] = resolved(t);
    for (const auto& [s, t] : aggItemTypes_) out_->aggItems[s] = resolved(t);
    for (const auto& [name, t] : constTypes_) out_->consts[name] = resolved(t);
  }

  const Program& p_;
  Diagnostics& diag_;
  Typing* out_ = nullptr;
  std::unordered_map<const Expr*, int> exprTypes_;
  std::unordered_map<const AggSpec*, int> aggItemTypes_;
  std::vector<TypeNode> types_;
  std::unordered_map<Symbol, const TypeExpr*> aliases_;
  std::unordered_map<Symbol, const PredicateDecl*> preds_;
  std::unordered_map<Symbol, const FunDecl*> funs_;
  std::unordered_map<Symbol, const ExternDecl*> externs_;
  std::unordered_map<Symbol, const ConstDecl*> constDecls_;
  std::unordered_map<Symbol, int> constTypes_;
};

}  // namespace

void checkTypes(const Program& program, Diagnostics& diag) { Checker(program, diag).run(); }

Typing inferTypes(const Program& program, Diagnostics& diag) {
  Typing typing;
  Checker(program, diag, &typing).run();
  return typing;
}

}  // namespace meldc
