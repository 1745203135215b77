// Lowering of the declarations (§4): the type and predicate tables, the initial nodes, scheduling
// directives, indexes and user externs. Also the small helpers of Lowering.
#include <algorithm>
#include <functional>
#include <unordered_set>

#include "lower_context.hpp"
#include "meldc/builtins.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

Instruction instructionOf(std::string_view name) {
  static const std::map<std::string_view, Instruction> table = {
      {"set-priority", Instruction::SetPriority},
      {"add-priority", Instruction::AddPriority},
      {"remove-priority", Instruction::RemovePriority},
      {"set-default-priority", Instruction::SetDefaultPriority},
      {"schedule-next", Instruction::ScheduleNext},
      {"set-static", Instruction::SetStatic},
      {"set-moving", Instruction::SetMoving},
      {"set-affinity", Instruction::SetAffinity},
      {"set-cpu", Instruction::SetCpu},
      {"stop-program", Instruction::StopProgram},
  };
  auto it = table.find(name);
  return it == table.end() ? Instruction::None : it->second;
}

// Calls f on every subgoal of the program (bodies, heads, nested constructs).
void forEachSubgoal(const std::vector<Term>& terms, const std::function<void(const Term&)>& f) {
  for (const Term& t : terms) {
    if (t.kind == TermKind::Subgoal) f(t);
    forEachSubgoal(t.body, f);
    forEachSubgoal(t.perMatch, f);
    forEachSubgoal(t.head, f);
    forEachSubgoal(t.elseHead, f);
  }
}

meldvm::AggregateKind aggregateKind(FieldAgg a) {
  switch (a) {
    case FieldAgg::Min:
      return meldvm::AggregateKind::Min;
    case FieldAgg::Max:
      return meldvm::AggregateKind::Max;
    case FieldAgg::Sum:
      return meldvm::AggregateKind::Sum;
    case FieldAgg::First:
      return meldvm::AggregateKind::First;
    case FieldAgg::None:
      break;
  }
  return meldvm::AggregateKind::None;
}

void addPredicate(Lowering& L, Symbol key, meldvm::PredicateDesc desc, const PredicateDecl* decl,
                  SourceLoc loc) {
  try {
    PredInfo info;
    info.id = L.prog.predicates.add(std::move(desc));
    info.decl = decl;
    L.preds[key] = info;
  } catch (const std::invalid_argument& e) {
    L.diag.error(loc, std::string(e.what()).substr(std::string("meldvm: ").size()));
  }
}

void predicates(Lowering& L) {
  // Compact predicates (§4.4) and the names the program uses.
  std::unordered_set<Symbol> compact;
  for (const Directive& d : L.ast.directives)
    if (d.kind == DirectiveKind::Compact) compact.insert(d.sym);
  std::unordered_set<Symbol> used;
  for (const Rule& r : L.ast.rules) {
    auto note = [&](const Term& t) { used.insert(t.sym); };
    forEachSubgoal(r.body, note);
    forEachSubgoal(r.head, note);
  }
  std::unordered_set<Symbol> declared;
  for (const PredicateDecl& d : L.ast.predicates) declared.insert(d.sym);
  auto threadHome = [&](const PredicateDecl& d) {
    return !d.fields.empty() && L.vmType(d.fields[0].type) == meldvm::TypeTable::kThread;
  };

  // §6.2: a program has thread predicates when it declares one or mentions a built-in one; only
  // then do thread nodes (and `_init_thread`, rule 1) exist.
  for (const PredicateDecl& d : L.ast.predicates) L.threads |= threadHome(d);
  for (const BuiltinPredicate& b : builtinPredicates())
    L.threads |=
        b.thread && used.count(L.ast.symbols.find(b.name)) && !declared.count(L.ast.symbols.find(b.name));

  // cl-meld's order (§9.3): _init, the used built-ins in table order, the declarations in
  // program order (generated predicates of localization come last there).
  for (const BuiltinPredicate& b : builtinPredicates()) {
    std::string name(b.name);
    const Symbol sym = L.ast.symbols.find(name);
    if (b.kind == BuiltinPredKind::Instruction) {
      L.preds[sym] = PredInfo{meldvm::Program::kNoPred, instructionOf(name), nullptr};
      continue;
    }
    if (declared.count(sym)) continue;  // a declaration redefines the built-in
    const bool always = name == "_init" || (name == "_init_thread" && L.threads);
    if (!always && !used.count(sym)) continue;
    meldvm::PredicateDesc desc;
    desc.name = name;
    desc.linear = b.kind == BuiltinPredKind::Linear;
    desc.action = b.action;
    desc.thread = b.thread;
    // The special thread facts are provided by the VM and stored compactly (§4.1.3, §4.4).
    desc.compact = b.thread && !desc.linear;
    if (name == "setcolor")
      desc.fields = {meldvm::TypeTable::kInt, meldvm::TypeTable::kInt, meldvm::TypeTable::kInt};
    else if (name == "setedgelabel")
      desc.fields = {meldvm::TypeTable::kNode, meldvm::TypeTable::kString};
    else if (name == "write-string")
      desc.fields = {meldvm::TypeTable::kString};
    else if (name == "setcolor2")
      desc.fields = {meldvm::TypeTable::kInt};
    else if (name == "thread-list")
      desc.fields = {L.prog.types.list(meldvm::TypeTable::kThread)};
    else if (name == "other-thread")
      desc.fields = {meldvm::TypeTable::kThread, meldvm::TypeTable::kInt};
    else if (name == "leader-thread")
      desc.fields = {meldvm::TypeTable::kThread};
    addPredicate(L, sym, std::move(desc), nullptr, {});
  }
  for (const PredicateDecl& d : L.ast.predicates) {
    if (d.fields.empty()) continue;
    meldvm::PredicateDesc desc;
    desc.name = d.name;
    desc.linear = d.linear;
    desc.route = d.route;
    desc.action = d.action;
    desc.reverseRoute = d.reverseRoute;  // generated ___xxx inverse routes (§6.7)
    desc.thread = threadHome(d);         // facts live at thread nodes (§6.12)
    // cl-meld stores only persistent facts compactly; on a linear predicate the directive is moot.
    desc.compact = compact.count(d.sym) > 0 && !d.linear;
    for (size_t i = 1; i < d.fields.size(); ++i) {
      desc.fields.push_back(L.vmType(d.fields[i].type));
      if (d.fields[i].agg != FieldAgg::None) {
        desc.aggregate = aggregateKind(d.fields[i].agg);
        desc.aggregateField = std::uint32_t(i - 1);
      }
    }
    addPredicate(L, d.sym, std::move(desc), &d, d.nameLoc);
  }
  if (const PredInfo* init = L.builtinPred("_init")) L.prog.initPredicate = init->id;
}

void directives(Lowering& L) {
  meldvm::SchedulingOptions& s = L.prog.scheduling;
  for (const Directive& d : L.ast.directives) {
    switch (d.kind) {
      case DirectiveKind::Index:
        if (d.position >= 2)
          if (const PredInfo* p = L.pred(d.sym); p && p->id != meldvm::Program::kNoPred)
            L.prog.indexes.push_back({p->id, std::uint32_t(d.position - 2)});
        break;
      case DirectiveKind::Data:
        break;  // imported as constant axioms by the front end (data_import.cpp)
      case DirectiveKind::Priority:
        switch (d.priority) {
          case PriorityKind::OrderAsc:
            s.order = meldvm::PriorityOrder::Asc;
            break;
          case PriorityKind::OrderDesc:
            s.order = meldvm::PriorityOrder::Desc;
            break;
          case PriorityKind::Initial:
            s.hasInitialPriority = true;
            s.initialPriority = d.value;
            break;
          case PriorityKind::Default:
            s.hasDefaultPriority = true;
            s.defaultPriority = d.value;
            break;
          case PriorityKind::NoInitial:
            s.noInitialPriorities = true;
            break;
          case PriorityKind::Static:
            s.staticNodes = true;
            break;
          case PriorityKind::NoPriority:
            s.hasNoPriority = true;
            s.noPriority = d.value;
            break;
          default:  // cluster: node numbering (done); a < b: stratum levels the VM ignores
            break;
        }
        break;
      default:  // compact: in the predicate table; allocator: a hint
        break;
    }
  }
}

}  // namespace

const PredInfo* Lowering::pred(Symbol name) const {
  auto it = preds.find(name);
  return it == preds.end() ? nullptr : &it->second;
}

const PredInfo* Lowering::builtinPred(std::string_view name) const { return pred(ast.symbols.find(name)); }

meldvm::TypeId Lowering::vmType(const TypeExpr& t) {
  using meldvm::TypeTable;
  auto elem = [&]() { return t.args.empty() ? TypeTable::kInt : vmType(t.args[0]); };
  switch (t.kind) {
    case TypeKind::Int:
      return TypeTable::kInt;
    case TypeKind::Float:
      return TypeTable::kFloat;
    case TypeKind::Bool:
      return TypeTable::kBool;
    case TypeKind::String:
      return TypeTable::kString;
    case TypeKind::Node:
      return TypeTable::kNode;
    case TypeKind::Thread:
      return TypeTable::kThread;
    case TypeKind::List:
      return prog.types.list(elem());
    case TypeKind::Set:
      return prog.types.set(elem());
    case TypeKind::Array:
      return prog.types.array(elem());
    case TypeKind::Struct: {
      std::vector<meldvm::TypeId> fields;
      for (const TypeExpr& a : t.args) fields.push_back(vmType(a));
      return prog.types.structOf(fields);
    }
    case TypeKind::Named:
      for (const TypeAliasDecl& a : ast.typeAliases)
        if (a.sym == t.sym) return vmType(a.type);
      return TypeTable::kNode;  // a node subtype
  }
  return TypeTable::kInt;
}

meldvm::TypeId Lowering::typeOf(const Expr& e) {
  const TypeExpr* t = typing.of(e);
  if (!t) throw LowerError(e.loc, "internal error: expression without an inferred type");
  return vmType(*t);
}

std::uint32_t Lowering::string(const std::string& s) {
  auto [it, added] = strings.emplace(s, std::uint32_t(prog.strings.size()));
  if (added) prog.strings.push_back(s);
  return it->second;
}

std::string Lowering::label(SourceLoc loc) const {
  if (!loc.valid() || loc.file >= sources.size()) return "";
  std::string_view line = sources.line(loc.file, loc.line);
  std::string text(line.substr(std::min<size_t>(loc.col ? loc.col - 1 : 0, line.size())));
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.pop_back();
  return text;
}

void Lowering::at(CodeBuilder& cb, SourceLoc loc) {
  if (!loc.valid() || loc.file >= sources.size()) return;
  auto [it, added] = sourceFileIndex.try_emplace(loc.file, std::uint32_t(prog.sourceFiles.size()));
  if (added) prog.sourceFiles.push_back(sources.file(loc.file).path);
  cb.at(it->second, loc.line);
}

void lowerDeclarations(Lowering& L) {
  predicates(L);
  directives(L);
  for (const NodeId& n : L.ast.nodeTable) L.prog.nodeSourceIds.push_back(n.source);
  L.prog.nodeAxioms.assign(L.prog.nodeSourceIds.size(), meldvm::Program::kNoAxioms);
  for (const ExternDecl& e : L.ast.externs) {
    meldvm::Extern x;
    x.name = e.name;
    for (const FieldDecl& f : e.params) x.params.push_back(L.vmType(f.type));
    x.result = L.vmType(e.result);
    L.externs[e.sym] = std::uint32_t(L.prog.externs.size());
    L.prog.externs.push_back(std::move(x));
  }
}

}  // namespace meldc
