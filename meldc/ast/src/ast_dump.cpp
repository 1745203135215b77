#include "meldc/ast_dump.hpp"

#include <cstdio>
#include <sstream>

namespace meldc {

using namespace meldc::ast;

namespace {

std::string joinExprs(const std::vector<Expr>& xs, size_t count) {
  std::string out;
  for (size_t i = 0; i < count && i < xs.size(); ++i) {
    if (i) out += ", ";
    out += toString(xs[i]);
  }
  return out;
}

std::string joinVars(const std::vector<VarDecl>& vars) {
  std::string out;
  for (size_t i = 0; i < vars.size(); ++i) out += (i ? ", " : "") + vars[i].name;
  return out;
}

std::string joinTerms(const std::vector<Term>& ts) {
  if (ts.empty()) return "1";
  std::string out;
  for (size_t i = 0; i < ts.size(); ++i) out += (i ? ", " : "") + toString(ts[i]);
  return out;
}

const char* markSpelling(Mark m) {
  switch (m) {
    case Mark::Persistent:
      return "!";
    case Mark::Linear:
      return "?";
    case Mark::Reuse:
      return "$";
    default:
      return "";
  }
}

const char* aggOpName(AggOp op) {
  switch (op) {
    case AggOp::Sum:
      return "sum";
    case AggOp::Count:
      return "count";
    case AggOp::Collect:
      return "collect";
    case AggOp::Min:
      return "min";
    case AggOp::Custom:
      return "custom";
  }
  return "?";
}

const char* fieldAggName(FieldAgg a) {
  switch (a) {
    case FieldAgg::Min:
      return "min ";
    case FieldAgg::Max:
      return "max ";
    case FieldAgg::Sum:
      return "sum ";
    case FieldAgg::First:
      return "first ";
    default:
      return "";
  }
}

// Built by appending: GCC 12 -O3 warns (-Wrestrict, a false positive) on "literal" + std::string&&.
std::string where(SourceLoc loc) {
  std::string s = "[";
  s += std::to_string(loc.line);
  s += ':';
  s += std::to_string(loc.col);
  s += ']';
  return s;
}

std::string fieldList(const std::vector<FieldDecl>& fields) {
  std::string out;
  for (size_t i = 0; i < fields.size(); ++i) {
    out += (i ? ", " : "") + std::string(fieldAggName(fields[i].agg)) + toString(fields[i].type);
    if (!fields[i].argName.empty()) out += " " + fields[i].argName;
  }
  return out;
}

std::string formatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

class Dumper {
 public:
  explicit Dumper(std::ostream& out) : out_(out) {}

  void terms(const std::vector<Term>& ts, int depth) {
    if (ts.empty()) line(depth, "1 (empty)");
    for (const Term& t : ts) term(t, depth);
  }

  void term(const Term& t, int depth) {
    switch (t.kind) {
      case TermKind::Subgoal: {
        std::string s = "subgoal " + std::string(markSpelling(t.mark)) + t.name + "(" +
                        joinExprs(t.args, t.args.size()) + ")";
        if (t.delayMs) s += " @+" + std::to_string(*t.delayMs) + "ms";
        line(depth, s + " " + where(t.loc));
        break;
      }
      case TermKind::Constraint:
        line(depth, "constraint " + toString(t.cond) + " " + where(t.loc));
        break;
      case TermKind::Exists:
        line(depth, "exists " + joinVars(t.vars) + " " + where(t.loc));
        terms(t.head, depth + 1);
        break;
      case TermKind::Comprehension:
        line(depth, "comprehension {" + joinVars(t.vars) + "} " + where(t.loc));
        line(depth + 1, "body");
        terms(t.body, depth + 2);
        line(depth + 1, "head");
        terms(t.head, depth + 2);
        break;
      case TermKind::Aggregate: {
        std::string specs;
        for (size_t i = 0; i < t.specs.size(); ++i) {
          const AggSpec& s = t.specs[i];
          specs += (i ? ", " : "") + std::string(aggOpName(s.op));
          if (s.op == AggOp::Custom) specs += " " + s.function + " " + toString(s.start);
          specs += " => " + s.var;
        }
        static const char* shapes = "ABCDEFG";
        line(depth, "aggregate [" + specs + "] vars {" + joinVars(t.vars) + "} shape " +
                        shapes[static_cast<int>(t.shape)] + " " + where(t.loc));
        line(depth + 1, "body");
        terms(t.body, depth + 2);
        if (t.shape == AggShape::D || t.shape == AggShape::F) {
          line(depth + 1, "per-match head");
          terms(t.perMatch, depth + 2);
        }
        if (t.shape != AggShape::G) {
          line(depth + 1, "head");
          terms(t.head, depth + 2);
        }
        break;
      }
      case TermKind::Conditional:
        line(depth, "if " + toString(t.cond) + " " + where(t.loc));
        line(depth + 1, "then");
        terms(t.head, depth + 2);
        line(depth + 1, "otherwise");
        terms(t.elseHead, depth + 2);
        break;
    }
  }

  void line(int depth, const std::string& text) { out_ << std::string(2 * depth, ' ') << text << '\n'; }

 private:
  std::ostream& out_;
};

}  // namespace

std::string toString(const TypeExpr& t) {
  switch (t.kind) {
    case TypeKind::Int:
      return "int";
    case TypeKind::Float:
      return "float";
    case TypeKind::Bool:
      return "bool";
    case TypeKind::String:
      return "string";
    case TypeKind::Node:
      return "node";
    case TypeKind::Thread:
      return "thread";
    case TypeKind::Named:
      return t.name;
    case TypeKind::List:
      return "list " + toString(t.args.at(0));
    case TypeKind::Set:
      return "set " + toString(t.args.at(0));
    case TypeKind::Array:
      return "array " + toString(t.args.at(0));
    case TypeKind::Struct: {
      std::string out = ":(";
      for (size_t i = 0; i < t.args.size(); ++i) out += (i ? ", " : "") + toString(t.args[i]);
      return out + ")";
    }
  }
  return "?";
}

std::string toString(const Expr& e) {
  switch (e.kind) {
    case ExprKind::Var:
      return e.name;
    case ExprKind::Anon:
      return "_";
    case ExprKind::Int:
      return std::to_string(e.intValue);
    case ExprKind::Float:
      return e.text;
    case ExprKind::Bool:
      return e.boolValue ? "true" : "false";
    case ExprKind::String:
      return "\"" + e.name + "\"";
    case ExprKind::Node:
      return "@" + std::to_string(e.intValue);
    case ExprKind::World:
      return "@world";
    case ExprKind::Cpus:
      return "@cpus";
    case ExprKind::Host:
      return "@host";
    case ExprKind::Thread:
      return "@thread";
    case ExprKind::Arg:
      return "@arg" + std::to_string(e.intValue);
    case ExprKind::Const:
      return e.name;
    case ExprKind::Call:
      return e.name + "(" + joinExprs(e.args, e.args.size()) + ")";
    case ExprKind::Convert:
      return "float(" + joinExprs(e.args, 1) + ")";
    case ExprKind::Binary:
    case ExprKind::Compare:
      return "(" + toString(e.args.at(0)) + " " + binOpSpelling(e.op) + " " + toString(e.args.at(1)) + ")";
    case ExprKind::In:
      return "(" + toString(e.args.at(0)) + " in " + toString(e.args.at(1)) + ")";
    case ExprKind::Ins:
      return "(" + toString(e.args.at(0)) + " ins " + toString(e.args.at(1)) + ")";
    case ExprKind::Not:
      return "~" + toString(e.args.at(0));
    case ExprKind::And:
      return "(" + toString(e.args.at(0)) + " && " + toString(e.args.at(1)) + ")";
    case ExprKind::Or:
      return "(" + toString(e.args.at(0)) + " || " + toString(e.args.at(1)) + ")";
    case ExprKind::If:
      return "if " + toString(e.args.at(0)) + " then " + toString(e.args.at(1)) + " else " +
             toString(e.args.at(2)) + " end";
    case ExprKind::Let:
      return "let " + e.name + " = " + toString(e.args.at(0)) + " in " + toString(e.args.at(1)) + " end";
    case ExprKind::Struct:
      return ":(" + joinExprs(e.args, e.args.size()) + ")";
    case ExprKind::List: {
      if (e.nilKeyword) return "nil";
      if (!e.hasTail) return "[" + joinExprs(e.args, e.args.size()) + "]";
      return "[" + joinExprs(e.args, e.args.size() - 1) + " | " + toString(e.args.back()) + "]";
    }
  }
  return "?";
}

std::string toString(const Term& t) {
  switch (t.kind) {
    case TermKind::Subgoal: {
      std::string s =
          std::string(markSpelling(t.mark)) + t.name + "(" + joinExprs(t.args, t.args.size()) + ")";
      if (t.delayMs) s += "@+" + std::to_string(*t.delayMs) + "ms";
      return s;
    }
    case TermKind::Constraint:
      return toString(t.cond);
    case TermKind::Exists:
      return "exists " + joinVars(t.vars) + ". (" + joinTerms(t.head) + ")";
    case TermKind::Comprehension:
      return "{" + joinVars(t.vars) + " | " + joinTerms(t.body) + " | " + joinTerms(t.head) + "}";
    case TermKind::Aggregate: {
      std::string s = "[";
      for (size_t i = 0; i < t.specs.size(); ++i) {
        const AggSpec& spec = t.specs[i];
        s += (i ? ", " : "") + std::string(aggOpName(spec.op));
        if (spec.op == AggOp::Custom) s += " " + spec.function + " " + toString(spec.start);
        s += " => " + spec.var;
      }
      if (!t.vars.empty()) s += " | " + joinVars(t.vars);
      s += " | " + joinTerms(t.body);
      if (t.shape == AggShape::D || t.shape == AggShape::F) s += " | " + joinTerms(t.perMatch);
      if (t.shape != AggShape::G) s += " | " + joinTerms(t.head);
      return s + "]";
    }
    case TermKind::Conditional:
      return "(if " + toString(t.cond) + " then " + joinTerms(t.head) + " otherwise " +
             joinTerms(t.elseHead) + " end)";
  }
  return "?";
}

void dumpProgram(const Program& p, const SourceManager& sources, std::ostream& out) {
  Dumper d(out);
  // Items of included files are marked with their file; the main file is file 0.
  auto at = [&](SourceLoc loc) {
    std::string s = where(loc);
    if (loc.file != 0 && loc.file < sources.size()) s = "[" + sources.file(loc.file).path + ":" + s.substr(1);
    return s;
  };
  out << "program: " << p.predicates.size() << " predicates, " << p.rules.size() << " rules and facts\n";
  for (const auto& i : p.includes) out << "include " << i.path << " " << at(i.loc) << '\n';
  for (const auto& n : p.nodeTypes) out << "node " << n.name << " " << at(n.loc) << '\n';
  for (const auto& a : p.typeAliases)
    out << "type alias " << a.name << " = " << toString(a.type) << " " << at(a.loc) << '\n';
  for (const auto& pd : p.predicates) {
    out << (pd.imported ? "import " : "type ");
    if (pd.linear) out << "linear ";
    if (pd.route) out << "route ";
    if (pd.reverseRoute) out << "reverse-route ";
    if (pd.action) out << "action ";
    out << pd.name << "(" << fieldList(pd.fields) << ")";
    if (pd.imported) out << " as-imported " << pd.importedName << " from " << pd.importedFrom;
    if (pd.generated) out << " generated";
    out << " " << at(pd.loc) << '\n';
  }
  for (const auto& e : p.exports) out << "export " << e.name << " " << at(e.loc) << '\n';
  for (const auto& dir : p.directives) {
    out << "directive ";
    switch (dir.kind) {
      case DirectiveKind::Index:
        out << "index " << dir.name << "/" << dir.position;
        break;
      case DirectiveKind::Compact:
        out << "compact " << dir.name;
        break;
      case DirectiveKind::Data:
        out << "data " << dir.name << " \"" << dir.text << "\"";
        for (const auto& a : dir.dataArgs) out << " \"" << a << "\"";
        break;
      case DirectiveKind::Allocator:
        out << "allocator \"" << dir.text << "\"";
        break;
      case DirectiveKind::Priority:
        out << "priority ";
        switch (dir.priority) {
          case PriorityKind::Static:
            out << "@static";
            break;
          case PriorityKind::ClusterStatic:
            out << "@cluster @static";
            break;
          case PriorityKind::ClusterRandom:
            out << "@cluster @random";
            break;
          case PriorityKind::NoInitial:
            out << "@no_initial_priorities";
            break;
          case PriorityKind::Initial:
            out << "@initial " << formatNumber(dir.value);
            break;
          case PriorityKind::Default:
            out << "@default " << formatNumber(dir.value);
            break;
          case PriorityKind::NoPriority:
            out << "@no_priority " << formatNumber(dir.value);
            break;
          case PriorityKind::OrderAsc:
            out << "@order @asc";
            break;
          case PriorityKind::OrderDesc:
            out << "@order @desc";
            break;
          case PriorityKind::Lower:
            out << dir.name << " < " << dir.other;
            break;
          case PriorityKind::Higher:
            out << dir.name << " > " << dir.other;
            break;
        }
        break;
    }
    out << " " << at(dir.loc) << '\n';
  }
  for (const auto& e : p.externs)
    out << "extern " << toString(e.result) << " " << e.name << "(" << fieldList(e.params) << ") " << at(e.loc)
        << '\n';
  for (const auto& c : p.consts)
    out << "const " << c.name << " = " << toString(c.value) << (c.fromCommandLine ? " (from -D)" : "") << " "
        << at(c.loc) << '\n';
  for (const auto& f : p.funs) {
    out << "fun " << f.name << "(";
    for (size_t i = 0; i < f.params.size(); ++i)
      out << (i ? ", " : "") << toString(f.params[i].type) << " " << f.params[i].name;
    out << ") : " << toString(f.result) << " = " << toString(f.body) << " " << at(f.loc) << '\n';
  }
  int index = 0;
  for (const auto& r : p.rules) {
    std::string kind = r.kind == RuleKind::Fact ? "fact" : r.kind == RuleKind::Linear ? "rule -o" : "rule :-";
    out << kind << " #" << index++ << (r.generated ? " generated " : " ") << at(r.loc) << '\n';
    if (r.selector)
      d.line(1, std::string("selector ") + (r.selector->kind == SelectorKind::Min ? ":min " : ":random ") +
                    r.selector->var);
    if (r.kind != RuleKind::Fact) {
      d.line(1, "body");
      d.terms(r.body, 2);
    }
    d.line(1, "head");
    d.terms(r.head, 2);
  }
}

}  // namespace meldc
