#include "meldc/renumber.hpp"

#include <algorithm>
#include <deque>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "support/splitmix.hpp"

namespace meldc {

namespace {

// A node literal of the program: where it is written, and its value for the rewrite.
struct NodeLiteral {
  SourceLoc loc;
  int64_t* value;
};

// Every node literal of the program, in program order.
class LiteralCollector {
 public:
  std::vector<NodeLiteral> literals;

  void program(ast::Program& p) {
    for (ast::ConstDecl& c : p.consts) expr(c.value);
    for (ast::FunDecl& f : p.funs) expr(f.body);
    ast::GroundFacts& ground = p.groundFacts;
    forEachStatement(
        p,
        [&](ast::Rule& r) {
          terms(r.body);
          terms(r.head);
        },
        [&](const ast::GroundFact& f) {
          for (size_t i = 0; i < f.argCount; ++i) {
            ast::GroundArg& a = ground.args[f.firstArg + i];
            if (a.kind == ast::GroundArg::Kind::Node)
              literals.push_back({SourceLoc{f.loc.file, a.line, a.col}, &a.i});
          }
        });
  }

 private:
  void expr(ast::Expr& e) {
    if (e.kind == ast::ExprKind::Node) literals.push_back({e.loc, &e.intValue});
    for (ast::Expr& a : e.args) expr(a);
  }
  void terms(std::vector<ast::Term>& ts) {
    for (ast::Term& t : ts) term(t);
  }
  void term(ast::Term& t) {
    for (ast::Expr& a : t.args) expr(a);
    expr(t.cond);
    for (ast::AggSpec& s : t.specs) expr(s.start);
    terms(t.body);
    terms(t.perMatch);
    terms(t.head);
    terms(t.elseHead);
  }
};

bool contains(const std::vector<int64_t>& v, int64_t x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// §6.1 step 1: per file, the distinct literal values in order of first textual occurrence.
std::map<uint32_t, std::vector<int64_t>> literalsPerFile(const std::vector<NodeLiteral>& literals) {
  auto before = [](const NodeLiteral& a, const NodeLiteral& b) {
    return std::tie(a.loc.file, a.loc.line, a.loc.col) < std::tie(b.loc.file, b.loc.line, b.loc.col);
  };
  std::vector<NodeLiteral> sorted(literals.begin(), literals.end());
  if (!std::is_sorted(sorted.begin(), sorted.end(), before))
    std::stable_sort(sorted.begin(), sorted.end(), before);
  std::map<uint32_t, std::vector<int64_t>> out;
  std::unordered_set<int64_t> seen;  // the values of the current file (`sorted` groups the files)
  uint32_t file = 0;
  for (const NodeLiteral& e : sorted) {
    if (e.loc.file != file) {
      seen.clear();
      file = e.loc.file;
    }
    if (seen.insert(*e.value).second) out[e.loc.file].push_back(*e.value);
  }
  return out;
}

// §6.1 step 2, recursively over the include tree.
class NodeMerger {
 public:
  NodeMerger(const ast::Program& p, const std::map<uint32_t, std::vector<int64_t>>& literals)
      : literals_(literals) {
    for (const ast::IncludeDecl& inc : p.includes)
      if (inc.file) includes_[inc.loc.file].push_back(*inc.file);
  }

  std::vector<int64_t> nodes(uint32_t file) {
    visited_.insert(file);
    std::vector<int64_t> out;
    if (auto it = literals_.find(file); it != literals_.end()) out = it->second;
    if (auto it = includes_.find(file); it != includes_.end())
      for (auto inc = it->second.rbegin(); inc != it->second.rend(); ++inc)
        if (!visited_.count(*inc)) out = sbclUnion(out, nodes(*inc));
    return out;
  }
  bool visited(uint32_t file) const { return visited_.count(file) != 0; }

 private:
  const std::map<uint32_t, std::vector<int64_t>>& literals_;
  std::map<uint32_t, std::vector<uint32_t>> includes_;  // file -> included files, in line order
  std::set<uint32_t> visited_;
};

// §6.1 step 4: E from the constant axioms of route predicates, in merged program order.
std::map<int64_t, std::vector<int64_t>> routeEdges(const ast::Program& p) {
  std::unordered_set<ast::Symbol> routes;
  for (const ast::PredicateDecl& d : p.predicates)
    if (d.route) routes.insert(d.sym);
  std::map<int64_t, std::deque<int64_t>> edges;
  std::vector<char> routeName;  // per ground fact name
  for (const ast::Symbol n : p.groundFacts.nameSyms) routeName.push_back(routes.count(n) ? 1 : 0);
  forEachStatement(
      p,
      [&](const ast::Rule& r) {
        if (r.kind != ast::RuleKind::Fact || !r.body.empty()) return;
        bool constant = !r.head.empty() && std::all_of(r.head.begin(), r.head.end(), [](const ast::Term& t) {
          return t.kind == ast::TermKind::Subgoal && !t.args.empty() && t.args[0].kind == ast::ExprKind::Node;
        });
        if (!constant) return;
        for (const ast::Term& t : r.head) {
          if (!routes.count(t.sym)) continue;
          for (size_t i = 1; i < t.args.size(); ++i) {
            if (t.args[i].kind != ast::ExprKind::Node) continue;
            edges[t.args[0].intValue].push_front(t.args[i].intValue);
            break;
          }
        }
      },
      [&](const ast::GroundFact& f) {
        if (!routeName[f.name]) return;
        for (size_t i = 1; i < f.argCount; ++i) {
          const ast::GroundArg& a = p.groundFacts.arg(f, i);
          if (a.kind != ast::GroundArg::Kind::Node) continue;
          edges[p.groundFacts.arg(f, 0).i].push_front(a.i);
          break;
        }
      });
  std::map<int64_t, std::vector<int64_t>> out;
  for (auto& [from, to] : edges) out[from].assign(to.begin(), to.end());
  return out;
}

}  // namespace

std::vector<int64_t> sbclUnion(const std::vector<int64_t>& x, const std::vector<int64_t>& y) {
  const std::vector<int64_t>& shorter = x.size() < y.size() ? x : y;
  const std::vector<int64_t>& longer = x.size() < y.size() ? y : x;
  std::deque<int64_t> result(shorter.begin(), shorter.end());
  for (int64_t e : longer)
    if (!contains(shorter, e)) result.push_front(e);
  return {result.begin(), result.end()};
}

std::vector<int64_t> numberBreadthFirst(const std::vector<int64_t>& order,
                                        std::map<int64_t, std::vector<int64_t>> edges) {
  std::vector<int64_t> out;
  std::unordered_set<int64_t> inP(order.begin(), order.end());
  size_t first = 0;  // P = the elements of `order` from `first` on that are still in inP
  auto advance = [&] {
    while (first < order.size() && !inP.count(order[first])) ++first;
  };
  std::deque<int64_t> queue;
  for (;;) {
    advance();
    if (edges.empty()) {
      for (size_t i = first; i < order.size(); ++i)
        if (inP.erase(order[i])) out.push_back(order[i]);
      break;
    }
    // The queue's nodes that are numbered already are dropped. Only the front matters: dropping
    // them as they reach it picks the same node as filtering the whole queue at every step, which
    // was quadratic in the number of edges.
    while (!queue.empty() && !inP.count(queue.front())) queue.pop_front();
    if (queue.empty() && first < order.size()) queue.push_back(order[first]);
    if (queue.empty()) break;
    int64_t n = queue.front();
    queue.pop_front();
    out.push_back(n);
    inP.erase(n);
    if (auto it = edges.find(n); it != edges.end()) {
      queue.insert(queue.end(), it->second.begin(), it->second.end());
      edges.erase(it);
    }
  }
  return out;
}

void renumberNodes(ast::Program& program, bool identity) {
  bool clusterStatic = identity;
  bool clusterRandom = false;
  for (const ast::Directive& d : program.directives) {
    if (d.kind == ast::DirectiveKind::Data) {
      clusterStatic = true;  // §6.1: node ids are those of the data file
    } else if (d.kind == ast::DirectiveKind::Priority && d.priority == ast::PriorityKind::ClusterRandom) {
      clusterRandom = true;
    } else if (d.kind == ast::DirectiveKind::Priority && d.priority == ast::PriorityKind::ClusterStatic) {
      clusterStatic = true;
    }
  }
  LiteralCollector collector;
  collector.program(program);
  std::map<uint32_t, std::vector<int64_t>> perFile = literalsPerFile(collector.literals);

  program.nodeTable.clear();
  if (clusterStatic) {
    int64_t max = -1;
    for (const NodeLiteral& e : collector.literals) max = std::max(max, *e.value);
    for (int64_t i = 0; i <= max; ++i) program.nodeTable.push_back({i, i});
    program.renumbered = true;
    return;
  }

  NodeMerger merger(program, perFile);
  std::vector<int64_t> mainNodes = merger.nodes(program.mainFile);
  // Literals outside the include tree (-D definitions) are added at the end of nodes(main).
  for (const auto& [file, list] : perFile) {
    if (merger.visited(file)) continue;
    for (int64_t n : list)
      if (!contains(mainNodes, n)) mainNodes.push_back(n);
  }
  std::vector<int64_t> order(mainNodes.rbegin(), mainNodes.rend());
  std::vector<int64_t> numbered = numberBreadthFirst(order, routeEdges(program));
  if (clusterRandom) {
    // §4.4 `priority @cluster @random`: a random permutation. The established compiler's is not
    // reproducible; this one is (Fisher-Yates over a fixed splitmix64 stream), so runs agree.
    support::SplitMix64 rng;
    for (std::size_t i = numbered.size(); i > 1; --i) std::swap(numbered[i - 1], numbered[rng.below(i)]);
  }

  std::unordered_map<int64_t, int64_t> internal;
  for (size_t i = 0; i < numbered.size(); ++i) {
    internal[numbered[i]] = static_cast<int64_t>(i);
    program.nodeTable.push_back({static_cast<int64_t>(i), numbered[i]});
  }
  for (const NodeLiteral& e : collector.literals) *e.value = internal.at(*e.value);
  program.renumbered = true;
}

}  // namespace meldc
