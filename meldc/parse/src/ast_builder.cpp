#include "ast_builder.hpp"

#include <cctype>
#include <charconv>
#include <cstdlib>
#include <string>

#include "meldc/case_folding.hpp"

namespace meldc {

using meldgen::MeldParser;
using namespace meldc::ast;

namespace {

enum Section { kInclude, kDefinition, kDirective, kExtern, kConst, kFun, kStatement };

const char* sectionName(int s) {
  switch (s) {
    case kInclude:
      return "include";
    case kDefinition:
      return "type declarations";
    case kDirective:
      return "directives";
    case kExtern:
      return "extern declarations";
    case kConst:
      return "const declarations";
    case kFun:
      return "fun definitions";
    default:
      return "rules and facts";
  }
}

const char* itemName(int s) {
  switch (s) {
    case kInclude:
      return "include";
    case kDefinition:
      return "type declaration";
    case kDirective:
      return "directive";
    case kExtern:
      return "extern declaration";
    case kConst:
      return "const declaration";
    case kFun:
      return "fun definition";
    default:
      return "rule";
  }
}

}  // namespace

SourceLoc AstBuilder::loc(antlr4::Token* token) const {
  SourceLoc l;
  l.file = file_;
  l.line = static_cast<uint32_t>(token->getLine());
  l.col = static_cast<uint32_t>(token->getCharPositionInLine()) + 1;
  return l;
}

int64_t AstBuilder::intLiteral(antlr4::Token* token, bool negative, int64_t min, int64_t max,
                               const char* what) {
  std::string text = token->getText();
  int64_t value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (negative) value = -value;
  if (ec != std::errc() || ptr != text.data() + text.size() || value < min || value > max) {
    diag_.error(loc(token), std::string(what) + " '" + (negative ? "-" : "") + text + "' is out of range");
    return 0;
  }
  return value;
}

// ------------------------------------------------------------------------------------------------
// Program and declarations

Program AstBuilder::buildProgram(MeldParser::ProgramContext* ctx) {
  Program program;
  for (auto* item : ctx->topItem()) topItem(item, program);
  return program;
}

Expr AstBuilder::buildExpr(MeldParser::ExprContext* ctx) { return expr(ctx); }

void AstBuilder::noteStatement() { section_ = kStatement; }

void AstBuilder::topItem(MeldParser::TopItemContext* ctx, Program& program) {
  int section = kStatement;
  if (ctx->includeDecl())
    section = kInclude;
  else if (ctx->definition())
    section = kDefinition;
  else if (ctx->directive())
    section = kDirective;
  else if (ctx->externDecl())
    section = kExtern;
  else if (ctx->constDecl())
    section = kConst;
  else if (ctx->funDecl())
    section = kFun;
  if (section < section_) {
    diag_.error(loc(ctx),
                std::string(itemName(section)) + " after " + sectionName(section_) +
                    "; a file lists includes, type declarations, directives, externs, consts, funs, "
                    "then rules and facts");
  } else {
    section_ = section;
  }

  if (auto* inc = ctx->includeDecl()) {
    IncludeDecl decl;
    decl.loc = loc(inc);
    std::string path = inc->FILE()->getText().substr(1);  // drop '#'
    if (auto comment = path.find("//"); comment != std::string::npos) path.erase(comment);
    while (!path.empty() && std::isspace(static_cast<unsigned char>(path.back()))) path.pop_back();
    size_t first = 0;
    while (first < path.size() && std::isspace(static_cast<unsigned char>(path[first]))) ++first;
    decl.path = path.substr(first);
    if (decl.path.empty())
      diag_.error(loc(inc->FILE()->getSymbol()), "include needs a file name after '#'");
    else
      program.includes.push_back(std::move(decl));
  } else if (auto* def = ctx->definition()) {
    definition(def, program);
  } else if (auto* dir = ctx->directive()) {
    directive(dir, program);
  } else if (auto* ext = ctx->externDecl()) {
    ExternDecl decl;
    decl.loc = loc(ext);
    decl.name = ext->name()->getText();
    decl.result = type(ext->typeExpr());
    if (ext->fieldDecls()) decl.params = fields(ext->fieldDecls());
    program.externs.push_back(std::move(decl));
  } else if (auto* c = ctx->constDecl()) {
    ConstDecl decl;
    decl.loc = loc(c);
    decl.name = c->name()->getText();
    decl.value = expr(c->expr());
    program.consts.push_back(std::move(decl));
  } else if (auto* f = ctx->funDecl()) {
    FunDecl decl;
    decl.loc = loc(f);
    decl.name = f->name()->getText();
    for (auto* p : f->funParam()) {
      FunParam param;
      param.loc = loc(p);
      param.type = type(p->typeExpr());
      param.name = p->VARIABLE()->getText();
      decl.params.push_back(std::move(param));
    }
    decl.result = type(f->typeExpr());
    decl.body = expr(f->expr());
    program.funs.push_back(std::move(decl));
  } else if (auto* s = ctx->statement()) {
    program.rules.push_back(statement(s));
  }
}

void AstBuilder::definition(MeldParser::DefinitionContext* ctx, Program& program) {
  if (auto* d = dynamic_cast<MeldParser::NodeTypeDefContext*>(ctx)) {
    program.nodeTypes.push_back(NodeTypeDecl{loc(d), d->name()->getText(), {}});
  } else if (auto* d = dynamic_cast<MeldParser::TypeAliasDefContext*>(ctx)) {
    program.typeAliases.push_back(TypeAliasDecl{loc(d), d->name()->getText(), type(d->typeExpr()), {}});
  } else if (auto* d = dynamic_cast<MeldParser::PredicateDefContext*>(ctx)) {
    PredicateDecl decl;
    decl.loc = loc(d);
    decl.name = d->name()->getText();
    decl.nameLoc = loc(d->name());
    for (auto* m : d->predModifier()) {
      if (m->K_LINEAR()) decl.linear = true;
      if (m->K_ROUTE()) decl.route = true;
      if (m->K_ACTION()) decl.action = true;
    }
    if (d->fieldDecls())
      decl.fields = fields(d->fieldDecls());
    else
      diag_.error(decl.nameLoc, "predicate '" + decl.name + "' needs at least one argument, its home node");
    program.predicates.push_back(std::move(decl));
  } else if (auto* d = dynamic_cast<MeldParser::ImportDefContext*>(ctx)) {
    PredicateDecl decl;
    decl.loc = loc(d);
    decl.imported = true;
    decl.importedName = d->name(0)->getText();
    decl.name = d->name(1)->getText();
    decl.nameLoc = loc(d->name(1));
    decl.importedFrom = d->name(2)->getText();
    for (auto* m : d->predModifier()) {
      if (m->K_LINEAR()) decl.linear = true;
      if (m->K_ROUTE()) decl.route = true;
      if (m->K_ACTION()) decl.action = true;
    }
    if (d->fieldDecls()) decl.fields = fields(d->fieldDecls());
    program.predicates.push_back(std::move(decl));
  } else if (auto* d = dynamic_cast<MeldParser::ExportDefContext*>(ctx)) {
    program.exports.push_back(ExportDecl{loc(d), d->name()->getText()});
  }
}

double AstBuilder::number(MeldParser::NumberContext* ctx) {
  std::string text = ctx->getText();
  return std::strtod(text.c_str(), nullptr);
}

void AstBuilder::directive(MeldParser::DirectiveContext* ctx, Program& program) {
  Directive d;
  d.loc = loc(ctx);
  if (auto* x = dynamic_cast<MeldParser::IndexDirectiveContext*>(ctx)) {
    d.kind = DirectiveKind::Index;
    d.name = x->name()->getText();
    d.nameLoc = loc(x->name());
    d.position = intLiteral(x->INT()->getSymbol(), false, 0, INT32_MAX, "field number");
  } else if (auto* x = dynamic_cast<MeldParser::CompactDirectiveContext*>(ctx)) {
    d.kind = DirectiveKind::Compact;
    d.name = x->name()->getText();
    d.nameLoc = loc(x->name());
  } else if (auto* x = dynamic_cast<MeldParser::DataDirectiveContext*>(ctx)) {
    d.kind = DirectiveKind::Data;
    d.name = x->name()->getText();
    d.nameLoc = loc(x->name());
    auto strings = x->STRING();
    for (size_t i = 0; i < strings.size(); ++i) {
      std::string s = strings[i]->getText();
      s = s.substr(1, s.size() - 2);
      if (i == 0)
        d.text = s;
      else
        d.dataArgs.push_back(s);
    }
  } else if (auto* x = dynamic_cast<MeldParser::AllocatorDirectiveContext*>(ctx)) {
    d.kind = DirectiveKind::Allocator;
    std::string s = x->STRING()->getText();
    d.text = s.substr(1, s.size() - 2);
  } else if (auto* x = dynamic_cast<MeldParser::PriorityDirectiveContext*>(ctx)) {
    d.kind = DirectiveKind::Priority;
    auto* arg = x->priorityArg();
    if (dynamic_cast<MeldParser::PrioStaticContext*>(arg))
      d.priority = PriorityKind::Static;
    else if (dynamic_cast<MeldParser::PrioClusterStaticContext*>(arg))
      d.priority = PriorityKind::ClusterStatic;
    else if (dynamic_cast<MeldParser::PrioClusterRandomContext*>(arg))
      d.priority = PriorityKind::ClusterRandom;
    else if (dynamic_cast<MeldParser::PrioNoInitialContext*>(arg))
      d.priority = PriorityKind::NoInitial;
    else if (auto* p = dynamic_cast<MeldParser::PrioInitialContext*>(arg)) {
      d.priority = PriorityKind::Initial;
      d.value = number(p->number());
    } else if (auto* p = dynamic_cast<MeldParser::PrioDefaultContext*>(arg)) {
      d.priority = PriorityKind::Default;
      d.value = number(p->number());
    } else if (auto* p = dynamic_cast<MeldParser::PrioNoPriorityContext*>(arg)) {
      d.priority = PriorityKind::NoPriority;
      d.value = number(p->number());
    } else if (dynamic_cast<MeldParser::PrioAscContext*>(arg))
      d.priority = PriorityKind::OrderAsc;
    else if (dynamic_cast<MeldParser::PrioDescContext*>(arg))
      d.priority = PriorityKind::OrderDesc;
    else if (auto* p = dynamic_cast<MeldParser::PrioRelationContext*>(arg)) {
      d.priority = p->op->getType() == MeldParser::LT ? PriorityKind::Lower : PriorityKind::Higher;
      d.name = p->name(0)->getText();
      d.nameLoc = loc(p->name(0));
      d.other = p->name(1)->getText();
      d.otherLoc = loc(p->name(1));
    }
  }
  program.directives.push_back(std::move(d));
}

TypeExpr AstBuilder::type(MeldParser::TypeExprContext* ctx) {
  TypeExpr t;
  t.loc = loc(ctx);
  if (dynamic_cast<MeldParser::IntTypeContext*>(ctx))
    t.kind = TypeKind::Int;
  else if (dynamic_cast<MeldParser::FloatTypeContext*>(ctx))
    t.kind = TypeKind::Float;
  else if (dynamic_cast<MeldParser::BoolTypeContext*>(ctx))
    t.kind = TypeKind::Bool;
  else if (dynamic_cast<MeldParser::StringTypeContext*>(ctx))
    t.kind = TypeKind::String;
  else if (dynamic_cast<MeldParser::NodeTypeContext*>(ctx))
    t.kind = TypeKind::Node;
  else if (dynamic_cast<MeldParser::ThreadTypeContext*>(ctx))
    t.kind = TypeKind::Thread;
  else if (auto* n = dynamic_cast<MeldParser::NamedTypeContext*>(ctx)) {
    t.kind = TypeKind::Named;
    t.name = n->name()->getText();
  } else if (auto* l = dynamic_cast<MeldParser::ListTypeContext*>(ctx)) {
    t.kind = TypeKind::List;
    t.args.push_back(type(l->typeExpr()));
  } else if (auto* s = dynamic_cast<MeldParser::SetTypeContext*>(ctx)) {
    t.kind = TypeKind::Set;
    t.args.push_back(type(s->typeExpr()));
  } else if (auto* a = dynamic_cast<MeldParser::ArrayTypeContext*>(ctx)) {
    t.kind = TypeKind::Array;
    t.args.push_back(type(a->typeExpr()));
  } else if (auto* s = dynamic_cast<MeldParser::StructTypeContext*>(ctx)) {
    t.kind = TypeKind::Struct;
    for (auto* f : s->typeExpr()) t.args.push_back(type(f));
  }
  return t;
}

std::vector<FieldDecl> AstBuilder::fields(MeldParser::FieldDeclsContext* ctx) {
  std::vector<FieldDecl> out;
  for (auto* f : ctx->fieldDecl()) {
    FieldDecl field;
    field.loc = loc(f);
    if (auto* mod = f->aggMod()) {
      std::string m = lower(mod->getText());
      if (m == "min")
        field.agg = FieldAgg::Min;
      else if (m == "max")
        field.agg = FieldAgg::Max;
      else if (m == "sum")
        field.agg = FieldAgg::Sum;
      else if (m == "first")
        field.agg = FieldAgg::First;
      else
        diag_.error(loc(mod), "unknown aggregate '" + mod->getText() +
                                  "' in a declaration (expected min, max, sum or first)");
    }
    field.type = type(f->typeExpr());
    if (f->VARIABLE()) field.argName = f->VARIABLE()->getText();
    out.push_back(std::move(field));
  }
  return out;
}

// ------------------------------------------------------------------------------------------------
// Statements and terms

Rule AstBuilder::statement(MeldParser::StatementContext* ctx) {
  Rule rule;
  rule.loc = loc(ctx);
  if (auto* s = dynamic_cast<MeldParser::SelectorRuleContext*>(ctx)) {
    rule.kind = RuleKind::Linear;
    auto* sel = s->selector();
    Selector selector;
    selector.loc = loc(sel);
    selector.kind = sel->kind->getType() == MeldParser::K_MIN ? SelectorKind::Min : SelectorKind::Random;
    selector.var = sel->VARIABLE()->getText();
    rule.selector = selector;
    rule.body = terms(sel->terms());
    if (s->head()) rule.head = head(s->head());
  } else if (auto* s = dynamic_cast<MeldParser::HeadlessDatalogRuleContext*>(ctx)) {
    rule.kind = RuleKind::Datalog;
    rule.body = terms(s->terms());
  } else if (auto* s = dynamic_cast<MeldParser::PlainStatementContext*>(ctx)) {
    if (s->LOLLI()) {
      rule.kind = RuleKind::Linear;
      rule.body = terms(s->terms(0));
      if (s->head()) rule.head = head(s->head());
    } else if (s->IMPLIEDBY()) {
      rule.kind = RuleKind::Datalog;
      rule.head = terms(s->terms(0));
      rule.body = terms(s->terms(1));
    } else {
      rule.kind = RuleKind::Fact;
      rule.head = terms(s->terms(0));
    }
  }
  return rule;
}

std::vector<Term> AstBuilder::terms(MeldParser::TermsContext* ctx) {
  std::vector<Term> out;
  if (!ctx) return out;
  for (auto* t : ctx->term()) out.push_back(std::move(visit(t).as<Term>()));
  return out;
}

std::vector<Term> AstBuilder::head(MeldParser::HeadContext* ctx) {
  if (!ctx) return {};
  if (auto* n = ctx->INT()) {
    if (n->getText() != "1")
      diag_.error(loc(n->getSymbol()), "only '1' may stand for an empty head (found '" + n->getText() + "')");
    return {};
  }
  return terms(ctx->terms());
}

std::vector<VarDecl> AstBuilder::varList(MeldParser::VarListContext* ctx) {
  std::vector<VarDecl> out;
  if (!ctx) return out;
  for (auto* v : ctx->VARIABLE()) out.push_back(VarDecl{loc(v->getSymbol()), v->getText()});
  return out;
}

antlrcpp::Any AstBuilder::visitSubgoalTerm(MeldParser::SubgoalTermContext* ctx) {
  Term t;
  t.kind = TermKind::Subgoal;
  t.loc = loc(ctx);
  switch (ctx->mark->getType()) {
    case MeldParser::BANG:
      t.mark = Mark::Persistent;
      break;
    case MeldParser::QUESTION:
      t.mark = Mark::Linear;
      break;
    default:
      t.mark = Mark::Reuse;
      break;
  }
  t.name = ctx->name()->getText();
  t.nameLoc = loc(ctx->name());
  t.args = args(ctx->args());
  delay(t, ctx->DELAY());
  return t;
}

void AstBuilder::delay(Term& t, antlr4::tree::TerminalNode* d) {
  if (d) {
    std::string text = d->getText();  // @+500ms or @+2s
    bool ms = text.size() > 2 && text.compare(text.size() - 2, 2, "ms") == 0;
    std::string digits = text.substr(2, text.size() - 2 - (ms ? 2 : 1));
    int64_t value = 0;
    auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || ptr != digits.data() + digits.size() || value > INT32_MAX) {
      diag_.error(loc(d->getSymbol()), "delay '" + text + "' is out of range");
      value = 0;
    }
    t.delayMs = ms ? value : value * 1000;
  }
}

antlrcpp::Any AstBuilder::visitExistsTerm(MeldParser::ExistsTermContext* ctx) {
  Term t;
  t.kind = TermKind::Exists;
  t.loc = loc(ctx);
  t.vars = varList(ctx->varList());
  t.head = terms(ctx->terms());
  return t;
}

antlrcpp::Any AstBuilder::visitComprehensionTerm(MeldParser::ComprehensionTermContext* ctx) {
  Term t;
  t.kind = TermKind::Comprehension;
  t.loc = loc(ctx);
  t.vars = varList(ctx->varList());
  t.body = terms(ctx->terms());
  t.head = head(ctx->head());
  return t;
}

antlrcpp::Any AstBuilder::visitAggregateTerm(MeldParser::AggregateTermContext* ctx) {
  Term t;
  t.kind = TermKind::Aggregate;
  t.loc = loc(ctx);
  for (auto* specCtx : ctx->aggSpec()) {
    AggSpec spec;
    spec.loc = loc(specCtx);
    if (auto* s = dynamic_cast<MeldParser::SimpleAggSpecContext*>(specCtx)) {
      std::string op = lower(s->op->getText());
      spec.var = s->VARIABLE()->getText();
      if (op == "sum")
        spec.op = AggOp::Sum;
      else if (op == "count")
        spec.op = AggOp::Count;
      else if (op == "collect")
        spec.op = AggOp::Collect;
      else if (op == "min")
        spec.op = AggOp::Min;
      else if (op == "max")
        diag_.error(
            spec.loc,
            "'max' is not available in aggregate constructs (only sum, count, collect, min and custom)");
      else
        diag_.error(spec.loc, "unknown aggregate '" + s->op->getText() +
                                  "' (expected sum, count, collect, min or custom)");
    } else if (auto* c = dynamic_cast<MeldParser::CustomAggSpecContext*>(specCtx)) {
      spec.op = AggOp::Custom;
      spec.function = c->name()->getText();
      spec.start = expr(c->expr());
      spec.var = c->VARIABLE()->getText();
    }
    t.specs.push_back(std::move(spec));
  }
  // Classify the sections: V = variable list, T = terms (or 1), E = empty.
  std::string shape;
  auto sections = ctx->aggSection();
  for (auto* s : sections) shape += s->varList() ? 'V' : s->head() ? 'T' : 'E';
  auto sectionTerms = [&](size_t i) { return head(sections[i]->head()); };
  if (shape == "TT") {
    t.shape = AggShape::A;
    t.body = sectionTerms(0);
    t.head = sectionTerms(1);
  } else if (shape == "TET") {
    t.shape = AggShape::B;
    t.body = sectionTerms(0);
    t.head = sectionTerms(2);
  } else if (shape == "VTT") {
    t.shape = AggShape::C;
    t.vars = varList(sections[0]->varList());
    t.body = sectionTerms(1);
    t.head = sectionTerms(2);
  } else if (shape == "VTTT") {
    t.shape = AggShape::D;
    t.vars = varList(sections[0]->varList());
    t.body = sectionTerms(1);
    t.perMatch = sectionTerms(2);
    t.head = sectionTerms(3);
  } else if (shape == "VTET") {
    t.shape = AggShape::E;
    t.vars = varList(sections[0]->varList());
    t.body = sectionTerms(1);
    t.head = sectionTerms(3);
  } else if (shape == "TTT") {
    t.shape = AggShape::F;
    t.body = sectionTerms(0);
    t.perMatch = sectionTerms(1);
    t.head = sectionTerms(2);
  } else if (shape == "VT") {
    t.shape = AggShape::G;
    t.vars = varList(sections[0]->varList());
    t.body = sectionTerms(1);
  } else {
    diag_.error(t.loc,
                "malformed aggregate; expected [specs | body | head], [specs | vars | body | head], "
                "[specs | vars | body | per-match head | head] or [specs | vars | body]");
  }
  return t;
}

antlrcpp::Any AstBuilder::visitConditionalTerm(MeldParser::ConditionalTermContext* ctx) {
  Term t;
  t.kind = TermKind::Conditional;
  t.loc = loc(ctx);
  t.cond = cond(ctx->cond());
  t.head = head(ctx->head(0));
  t.elseHead = head(ctx->head(1));
  return t;
}

antlrcpp::Any AstBuilder::visitCondTerm(MeldParser::CondTermContext* ctx) {
  Term t;
  t.loc = loc(ctx);
  if (auto* call = dynamic_cast<MeldParser::CallCondContext*>(ctx->cond())) {
    // `p(X, Y)`: a subgoal, or a boolean function call; name resolution decides.
    t.kind = TermKind::Subgoal;
    t.name = call->name()->getText();
    t.nameLoc = loc(call->name());
    t.args = args(call->args());
    delay(t, ctx->DELAY());
    return t;
  }
  t.kind = TermKind::Constraint;
  t.cond = cond(ctx->cond());
  if (ctx->DELAY())
    diag_.error(loc(ctx->DELAY()->getSymbol()), "a delay can only follow a fact, not a condition");
  return t;
}

// ------------------------------------------------------------------------------------------------
// Expressions

Expr AstBuilder::expr(MeldParser::ExprContext* ctx) { return std::move(visit(ctx).as<Expr>()); }
Expr AstBuilder::cond(MeldParser::CondContext* ctx) { return std::move(visit(ctx).as<Expr>()); }
Expr AstBuilder::primary(MeldParser::PrimaryContext* ctx) { return std::move(visit(ctx).as<Expr>()); }

std::vector<Expr> AstBuilder::args(MeldParser::ArgsContext* ctx) {
  std::vector<Expr> out;
  if (!ctx) return out;
  for (auto* e : ctx->expr()) out.push_back(expr(e));
  return out;
}

Expr AstBuilder::binary(ExprKind kind, BinOp op, antlr4::Token* at, Expr lhs, Expr rhs) {
  Expr e;
  e.kind = kind;
  e.op = op;
  e.loc = loc(at);
  e.args.push_back(std::move(lhs));
  e.args.push_back(std::move(rhs));
  return e;
}

antlrcpp::Any AstBuilder::visitMulExpr(MeldParser::MulExprContext* ctx) {
  BinOp op = ctx->op->getType() == MeldParser::STAR    ? BinOp::Mul
             : ctx->op->getType() == MeldParser::SLASH ? BinOp::Div
                                                       : BinOp::Mod;
  return binary(ExprKind::Binary, op, ctx->op, expr(ctx->expr(0)), expr(ctx->expr(1)));
}

antlrcpp::Any AstBuilder::visitAddExpr(MeldParser::AddExprContext* ctx) {
  BinOp op = ctx->op->getType() == MeldParser::PLUS    ? BinOp::Add
             : ctx->op->getType() == MeldParser::MINUS ? BinOp::Sub
                                                       : BinOp::Append;
  return binary(ExprKind::Binary, op, ctx->op, expr(ctx->expr(0)), expr(ctx->expr(1)));
}

antlrcpp::Any AstBuilder::visitPrimaryExpr(MeldParser::PrimaryExprContext* ctx) {
  return primary(ctx->primary());
}

antlrcpp::Any AstBuilder::visitVarExpr(MeldParser::VarExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Var;
  e.loc = loc(ctx);
  e.name = ctx->getText();
  return e;
}

antlrcpp::Any AstBuilder::visitAnonExpr(MeldParser::AnonExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Anon;
  e.loc = loc(ctx);
  e.name = "_";
  return e;
}

antlrcpp::Any AstBuilder::visitArgExpr(MeldParser::ArgExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Arg;
  e.loc = loc(ctx);
  e.intValue = ctx->getText().back() - '0';
  if (e.intValue == 0)
    diag_.error(e.loc, "'@arg0' does not exist; program arguments are numbered from @arg1");
  return e;
}

antlrcpp::Any AstBuilder::visitTrueExpr(MeldParser::TrueExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Bool;
  e.loc = loc(ctx);
  e.boolValue = true;
  return e;
}

antlrcpp::Any AstBuilder::visitFalseExpr(MeldParser::FalseExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Bool;
  e.loc = loc(ctx);
  return e;
}

antlrcpp::Any AstBuilder::visitStringExpr(MeldParser::StringExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::String;
  e.loc = loc(ctx);
  std::string s = ctx->getText();
  e.name = s.substr(1, s.size() - 2);
  return e;
}

antlrcpp::Any AstBuilder::visitIntExpr(MeldParser::IntExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Int;
  e.loc = loc(ctx);
  bool negative = ctx->MINUS() != nullptr;
  e.intValue = intLiteral(ctx->INT()->getSymbol(), negative, INT32_MIN, INT32_MAX, "integer literal");
  e.text = (negative ? "-" : "") + ctx->INT()->getText();
  return e;
}

antlrcpp::Any AstBuilder::visitFloatExpr(MeldParser::FloatExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Float;
  e.loc = loc(ctx);
  e.text = (ctx->MINUS() ? "-" : "") + ctx->FLOAT()->getText();
  e.floatValue = std::strtod(e.text.c_str(), nullptr);
  return e;
}

antlrcpp::Any AstBuilder::visitCallExpr(MeldParser::CallExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Call;
  e.loc = loc(ctx);
  e.name = ctx->name()->getText();
  e.args = args(ctx->args());
  return e;
}

antlrcpp::Any AstBuilder::visitConstExpr(MeldParser::ConstExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Const;
  e.loc = loc(ctx);
  e.name = ctx->getText();
  return e;
}

antlrcpp::Any AstBuilder::visitNodeExpr(MeldParser::NodeExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Node;
  e.loc = loc(ctx);
  e.intValue = intLiteral(ctx->INT()->getSymbol(), false, 0, INT32_MAX, "node number");
  e.text = ctx->INT()->getText();
  return e;
}

antlrcpp::Any AstBuilder::visitSpecialExpr(MeldParser::SpecialExprContext* ctx) {
  Expr e;
  e.loc = loc(ctx);
  switch (ctx->kind->getType()) {
    case MeldParser::S_WORLD:
      e.kind = ExprKind::World;
      break;
    case MeldParser::S_CPUS:
      e.kind = ExprKind::Cpus;
      break;
    case MeldParser::S_HOST:
      e.kind = ExprKind::Host;
      break;
    default:
      e.kind = ExprKind::Thread;
      break;
  }
  return e;
}

antlrcpp::Any AstBuilder::visitParenExpr(MeldParser::ParenExprContext* ctx) { return expr(ctx->expr()); }

antlrcpp::Any AstBuilder::visitStructExpr(MeldParser::StructExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Struct;
  e.loc = loc(ctx);
  for (auto* x : ctx->expr()) e.args.push_back(expr(x));
  return e;
}

antlrcpp::Any AstBuilder::visitConvExpr(MeldParser::ConvExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Convert;
  e.loc = loc(ctx);
  e.name = "float";
  e.args.push_back(expr(ctx->expr()));
  return e;
}

antlrcpp::Any AstBuilder::visitIfExpr(MeldParser::IfExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::If;
  e.loc = loc(ctx);
  e.args.push_back(cond(ctx->cond()));
  e.args.push_back(expr(ctx->expr(0)));
  e.args.push_back(expr(ctx->expr(1)));
  return e;
}

antlrcpp::Any AstBuilder::visitLetExpr(MeldParser::LetExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::Let;
  e.loc = loc(ctx);
  e.name = ctx->VARIABLE()->getText();
  e.args.push_back(expr(ctx->expr(0)));
  e.args.push_back(expr(ctx->expr(1)));
  return e;
}

antlrcpp::Any AstBuilder::visitNilExpr(MeldParser::NilExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::List;
  e.loc = loc(ctx);
  e.nilKeyword = true;
  return e;
}

antlrcpp::Any AstBuilder::visitListExpr(MeldParser::ListExprContext* ctx) {
  Expr e;
  e.kind = ExprKind::List;
  e.loc = loc(ctx);
  for (auto* x : ctx->expr()) e.args.push_back(expr(x));
  e.hasTail = ctx->BAR() != nullptr;
  return e;
}

antlrcpp::Any AstBuilder::visitNotCond(MeldParser::NotCondContext* ctx) {
  Expr e;
  e.kind = ExprKind::Not;
  e.loc = loc(ctx);
  e.args.push_back(cond(ctx->cond()));
  return e;
}

antlrcpp::Any AstBuilder::visitAndCond(MeldParser::AndCondContext* ctx) {
  return binary(ExprKind::And, BinOp::Eq, ctx->AND()->getSymbol(), cond(ctx->cond(0)), cond(ctx->cond(1)));
}

antlrcpp::Any AstBuilder::visitOrCond(MeldParser::OrCondContext* ctx) {
  return binary(ExprKind::Or, BinOp::Eq, ctx->OR()->getSymbol(), cond(ctx->cond(0)), cond(ctx->cond(1)));
}

antlrcpp::Any AstBuilder::visitCompareCond(MeldParser::CompareCondContext* ctx) {
  BinOp op = BinOp::Eq;
  switch (ctx->op->getType()) {
    case MeldParser::EQ:
      op = BinOp::Eq;
      break;
    case MeldParser::NE:
      op = BinOp::Ne;
      break;
    case MeldParser::LT:
      op = BinOp::Lt;
      break;
    case MeldParser::LE:
      op = BinOp::Le;
      break;
    case MeldParser::GT:
      op = BinOp::Gt;
      break;
    default:
      op = BinOp::Ge;
      break;
  }
  return binary(ExprKind::Compare, op, ctx->op, expr(ctx->expr(0)), expr(ctx->expr(1)));
}

antlrcpp::Any AstBuilder::visitInCond(MeldParser::InCondContext* ctx) {
  ExprKind kind = ctx->op->getType() == MeldParser::K_IN ? ExprKind::In : ExprKind::Ins;
  return binary(kind, BinOp::Eq, ctx->op, expr(ctx->expr(0)), expr(ctx->expr(1)));
}

antlrcpp::Any AstBuilder::visitParenCond(MeldParser::ParenCondContext* ctx) { return cond(ctx->cond()); }

antlrcpp::Any AstBuilder::visitCallCond(MeldParser::CallCondContext* ctx) {
  Expr e;
  e.kind = ExprKind::Call;
  e.loc = loc(ctx);
  e.name = ctx->name()->getText();
  e.args = args(ctx->args());
  return e;
}

}  // namespace meldc
