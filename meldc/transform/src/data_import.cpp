#include "meldc/data_import.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <unordered_map>
#include <sstream>

#include "support/splitmix.hpp"

namespace meldc {

using namespace meldc::ast;

namespace {

struct Edge {
  std::int64_t src, dst;
  double weight;  // third column, when there is one
};

struct Graph {
  std::vector<Edge> edges;  // in file order
  std::int64_t maxId = -1;
};

Expr literal(ExprKind kind, SourceLoc loc, std::int64_t i = 0, double f = 0.0) {
  Expr e;
  e.kind = kind;
  e.loc = loc;
  e.intValue = i;
  e.floatValue = f;
  return e;
}
Expr nodeLit(std::int64_t id, SourceLoc loc) { return literal(ExprKind::Node, loc, id); }
Expr intLit(std::int64_t v, SourceLoc loc) { return literal(ExprKind::Int, loc, v); }
Expr floatLit(double v, SourceLoc loc) { return literal(ExprKind::Float, loc, 0, v); }

class Importer {
 public:
  Importer(Program& p, SourceManager& s, Diagnostics& d) : p_(p), sources_(s), diag_(d) {}

  void run(const Directive& d) {
    loc_ = d.loc;
    static const char* kTemplates[] = {"stanford-snap",          "stanford-sssp-snap",
                                       "stanford-snap-basic",    "stanford-snap-undirected",
                                       "stanford-snap-pagerank", "stanford-snap-search"};
    if (std::find(std::begin(kTemplates), std::end(kTemplates), d.name) == std::end(kTemplates)) {
      diag_.error(d.nameLoc, "unknown data template '" + d.name +
                                 "' (templates: stanford-snap, stanford-sssp-snap, stanford-snap-basic, "
                                 "stanford-snap-undirected, stanford-snap-pagerank, stanford-snap-search)");
      return;
    }
    Graph g;
    if (!read(d, g)) return;
    const std::string& t = d.name;
    if (t == "stanford-snap-pagerank") {
      pagerank(g);
    } else if (t == "stanford-snap-search") {
      search(d, g);
    } else {
      support::SplitMix64 rng;
      for (const Edge& e : g.edges) {
        std::vector<Expr> args{nodeLit(e.src, loc_), nodeLit(e.dst, loc_)};
        if (t == "stanford-snap") args.push_back(floatLit(double(1 + std::int64_t(rng.below(500))), loc_));
        if (t == "stanford-sssp-snap") args.push_back(floatLit(e.weight, loc_));
        fact("edge", args);
        if (t == "stanford-snap-undirected") fact("edge", {nodeLit(e.dst, loc_), nodeLit(e.src, loc_)});
      }
    }
    maxId_ = std::max(maxId_, g.maxId);
  }

  std::int64_t maxId() const { return maxId_; }

 private:
  bool read(const Directive& d, Graph& g) {
    std::filesystem::path path(d.text);
    if (path.is_relative()) path = std::filesystem::path(sources_.file(d.loc.file).path).parent_path() / path;
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      diag_.error(d.loc, "data file '" + path.string() + "' is a directory");
      return false;
    }
    std::ifstream in(path);
    if (!in) {
      diag_.error(d.loc, "cannot read the data file '" + path.string() + "'");
      return false;
    }
    const bool weighted = d.name == "stanford-sssp-snap";
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
      std::istringstream fields(line);
      std::string a, b, w;
      if (!(fields >> a) || a[0] == '#') continue;
      Edge e{0, 0, 1.0};
      const bool ok = (fields >> b) && id(a, e.src) && id(b, e.dst) && (!weighted || ((fields >> w) && number(w, e.weight)));
      if (!ok) {
        diag_.error(d.loc, path.string() + ":" + std::to_string(lineNo) + ": expected `source target" +
                               std::string(weighted ? " weight" : "") + "` (node ids 0.." +
                               std::to_string(kMaxId) + "), got '" + line + "'");
        return false;
      }
      g.maxId = std::max({g.maxId, e.src, e.dst});
      g.edges.push_back(e);
    }
    return true;
  }

  static constexpr std::int64_t kMaxId = (std::int64_t(1) << 31) - 2;
  static bool id(const std::string& s, std::int64_t& out) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size() && out >= 0 && out <= kMaxId;
  }
  static bool number(const std::string& s, double& out) {
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return !s.empty() && end == s.c_str() + s.size();
  }

  // The established compiler's facts and their order per node, on which the order of a node's
  // loops over them (and so async pagerank's results) depends: each node's distinct successors in
  // file order; its predecessors in the order the nodes first appear in the file (as either end of
  // an edge); both lists are then reversed (it pushes each fact onto a list), the predecessors'
  // `input` facts first. Weights are 1 / out-degree in single precision, as its literals are.
  void pagerank(const Graph& g) {
    std::vector<std::int64_t> appearance;
    std::unordered_map<std::int64_t, std::vector<std::int64_t>> out, in;
    auto see = [&](std::int64_t id) {
      if (out.try_emplace(id).second) appearance.push_back(id);
    };
    for (const Edge& e : g.edges) {
      see(e.src);
      see(e.dst);
      std::vector<std::int64_t>& succ = out[e.src];
      if (std::find(succ.begin(), succ.end(), e.dst) == succ.end()) succ.push_back(e.dst);
    }
    auto weight = [&](std::int64_t id) { return double(1.0f / float(out[id].size())); };
    for (std::int64_t m : appearance)
      for (std::int64_t succ : out[m]) in[succ].push_back(m);
    for (std::int64_t n : appearance) {
      const std::vector<std::int64_t>& pred = in[n];
      for (auto it = pred.rbegin(); it != pred.rend(); ++it)
        fact("input", {nodeLit(n, loc_), nodeLit(*it, loc_), floatLit(weight(*it), loc_)});
      const std::vector<std::int64_t>& succ = out[n];
      for (auto it = succ.rbegin(); it != succ.rend(); ++it)
        fact("output", {nodeLit(n, loc_), nodeLit(*it, loc_), floatLit(weight(n), loc_)});
    }
  }

  void search(const Directive& d, const Graph& g) {
    double fraction = 0;
    if (d.dataArgs.size() != 2 || !number(d.dataArgs[1], fraction) || fraction < 0 || fraction > 100) {
      diag_.error(d.loc, "stanford-snap-search needs two arguments: [\"searches\" \"fraction\"] with the fraction a "
                         "percentage in 0..100");
      return;
    }
    for (const Edge& e : g.edges) fact("edge", {nodeLit(e.src, loc_), nodeLit(e.dst, loc_)});
    support::SplitMix64 rng;
    const std::int64_t nodes = g.maxId + 1;
    const std::int64_t perSearch = std::int64_t(double(nodes) * fraction / 100.0);
    std::int64_t searchId = 0;
    for (std::int64_t n = 0; n < nodes; ++n) {
      fact("value", {nodeLit(n, loc_), intLit(n, loc_)});
      if (double(rng.below(100)) >= fraction) continue;
      std::vector<std::int64_t> targets;
      while (std::int64_t(targets.size()) < perSearch) {
        const std::int64_t t = std::int64_t(rng.below(std::uint64_t(nodes)));
        if (std::find(targets.begin(), targets.end(), t) == targets.end()) targets.push_back(t);
      }
      Expr list;
      list.kind = ExprKind::List;
      list.loc = loc_;
      for (auto it = targets.rbegin(); it != targets.rend(); ++it) list.args.push_back(intLit(*it, loc_));
      fact("search", {nodeLit(n, loc_), intLit(searchId++, loc_), list});
    }
  }

  void fact(const char* name, std::vector<Expr> args) {
    Term t;
    t.kind = TermKind::Subgoal;
    t.loc = t.nameLoc = loc_;
    t.name = name;
    t.args = std::move(args);
    Rule r;
    r.loc = loc_;
    r.kind = RuleKind::Fact;
    r.head.push_back(std::move(t));
    p_.rules.push_back(std::move(r));
  }

  Program& p_;
  SourceManager& sources_;
  Diagnostics& diag_;
  SourceLoc loc_;
  std::int64_t maxId_ = -1;
};

}  // namespace

bool hasDataDirective(const Program& program) {
  return std::any_of(program.directives.begin(), program.directives.end(),
                     [](const Directive& d) { return d.kind == DirectiveKind::Data; });
}

bool importData(Program& program, SourceManager& sources, Diagnostics& diag) {
  if (!hasDataDirective(program)) return true;
  Importer importer(program, sources, diag);
  for (const Directive& d : program.directives)  // run() appends to the rules only
    if (d.kind == DirectiveKind::Data) importer.run(d);
  return !diag.hasErrors();
}

}  // namespace meldc
