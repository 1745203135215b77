#include "meldc/ground_facts.hpp"

#include <algorithm>
#include <cstdlib>
#include <unordered_map>
#include <vector>

#include "meldc/builtins.hpp"

namespace meldc {

namespace {

using ast::GroundArg;

// The declaration a fact of `name` may be checked against here, or null when the usual checks
// must see the fact (unknown or twice declared, a built-in, imported, an action).
std::vector<const ast::PredicateDecl*> plainDeclarations(const ast::Program& p) {
  std::unordered_map<ast::Symbol, int> count;
  std::unordered_map<ast::Symbol, const ast::PredicateDecl*> decl;
  for (const ast::PredicateDecl& d : p.predicates) {
    ++count[d.sym];
    decl[d.sym] = &d;
  }
  for (const BuiltinPredicate& b : builtinPredicates()) count[p.symbols.find(b.name)] += 2;
  std::vector<const ast::PredicateDecl*> out;
  for (const ast::Symbol name : p.groundFacts.nameSyms) {
    auto it = decl.find(name);
    const ast::PredicateDecl* d = it == decl.end() ? nullptr : it->second;
    const bool plain = d && count[name] == 1 && !d->imported && !d->action && !d->generated &&
                       !d->fields.empty() && d->fields[0].type.kind == ast::TypeKind::Node;
    out.push_back(plain ? d : nullptr);
  }
  return out;
}

bool literalFits(ast::TypeKind field, GroundArg::Kind literal) {
  switch (field) {
    case ast::TypeKind::Int:
      return literal == GroundArg::Kind::Int;
    case ast::TypeKind::Float:
      return literal == GroundArg::Kind::Int || literal == GroundArg::Kind::Float;
    case ast::TypeKind::Node:
      return literal == GroundArg::Kind::Node;
    case ast::TypeKind::String:
      return literal == GroundArg::Kind::String;
    case ast::TypeKind::Bool:
      return literal == GroundArg::Kind::Bool;
    default:
      return false;  // subtypes, aliases, lists...: the type checker decides
  }
}

bool admitted(const ast::GroundFacts& facts, const ast::GroundFact& f, const ast::PredicateDecl* d) {
  if (!d || d->fields.size() != f.argCount) return false;
  if (d->linear && f.persistentMark) return false;
  for (std::size_t i = 0; i < f.argCount; ++i)
    if (!literalFits(d->fields[i].type.kind, facts.arg(f, i).kind)) return false;
  return true;
}

// Rebuilds the rules with the facts for which keep() is false turned into rules, in place.
template <class Keep>
void materializeUnless(ast::Program& p, const SourceManager& sources, Keep keep) {
  ast::GroundFacts& facts = p.groundFacts;
  // Usually every fact stays compact: one pass that stops at the first exception decides it.
  if (std::all_of(facts.facts.begin(), facts.facts.end(), keep)) return;
  std::vector<ast::Rule> rules;
  rules.reserve(p.rules.size());
  std::vector<ast::GroundFact> kept;
  std::size_t next = 0;
  for (std::size_t i = 0; i <= p.rules.size(); ++i) {
    for (; next < facts.facts.size() && facts.facts[next].position == i; ++next) {
      ast::GroundFact f = facts.facts[next];
      if (keep(f)) {
        f.position = static_cast<std::uint32_t>(rules.size());
        kept.push_back(f);
      } else {
        rules.push_back(groundFactRule(facts, f, sources));
      }
    }
    if (i < p.rules.size()) rules.push_back(std::move(p.rules[i]));
  }
  p.rules = std::move(rules);
  facts.facts = std::move(kept);
  if (facts.facts.empty()) facts = ast::GroundFacts{};
}

}  // namespace

ast::Rule groundFactRule(const ast::GroundFacts& facts, const ast::GroundFact& fact,
                         const SourceManager& sources) {
  const std::string& text = sources.file(fact.loc.file).text;
  ast::Term t;
  t.kind = ast::TermKind::Subgoal;
  t.loc = fact.loc;
  t.mark = fact.persistentMark ? ast::Mark::Persistent : ast::Mark::None;
  t.name = facts.name(fact);
  if (fact.name < facts.nameSyms.size()) t.sym = facts.nameSyms[fact.name];
  t.nameLoc = SourceLoc{fact.loc.file, fact.loc.line, fact.nameCol};
  for (std::size_t i = 0; i < fact.argCount; ++i) {
    const GroundArg& a = facts.arg(fact, i);
    const std::string spelling = text.substr(a.offset, a.length);
    ast::Expr e;
    e.loc = SourceLoc{fact.loc.file, a.line, a.col};
    switch (a.kind) {
      case GroundArg::Kind::Int:
        e.kind = ast::ExprKind::Int;
        e.intValue = a.i;
        e.text = spelling;
        break;
      case GroundArg::Kind::Float:
        e.kind = ast::ExprKind::Float;
        e.text = spelling;
        e.floatValue = std::strtod(e.text.c_str(), nullptr);
        break;
      case GroundArg::Kind::Node:
        e.kind = ast::ExprKind::Node;
        e.intValue = a.i;
        e.text = spelling.substr(1);  // without the '@'
        break;
      case GroundArg::Kind::String:
        e.kind = ast::ExprKind::String;
        e.name = spelling.substr(1, spelling.size() - 2);
        break;
      case GroundArg::Kind::Bool:
        e.kind = ast::ExprKind::Bool;
        e.boolValue = a.i != 0;
        break;
    }
    t.args.push_back(std::move(e));
  }
  ast::Rule r;
  r.loc = fact.loc;
  r.kind = ast::RuleKind::Fact;
  r.head.push_back(std::move(t));
  return r;
}

void admitGroundFacts(ast::Program& program, const SourceManager& sources) {
  if (program.groundFacts.empty()) return;
  const std::vector<const ast::PredicateDecl*> decls = plainDeclarations(program);
  const ast::GroundFacts& facts = program.groundFacts;
  materializeUnless(program, sources,
                    [&](const ast::GroundFact& f) { return admitted(facts, f, decls[f.name]); });
}

void materializeGroundFacts(ast::Program& program, const SourceManager& sources) {
  materializeUnless(program, sources, [](const ast::GroundFact&) { return false; });
}

}  // namespace meldc
