#include "meldvm/derivation_log.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <ostream>
#include <set>
#include <stdexcept>

namespace meldvm {

namespace {

// Without blanks outside string literals: "a(1, \"x y\")" and "a(1,\"x y\")" compare equal.
std::string squeeze(const std::string& s) {
  std::string out;
  bool quoted = false;
  for (const char c : s) {
    if (c == '"') quoted = !quoted;
    if (!quoted && std::isspace(static_cast<unsigned char>(c))) continue;
    out += c;
  }
  return out;
}

// "!dist(3)" at node 5 -> "!dist(@5, 3)".
std::string userForm(const FactAt& f) {
  const auto open = f.text.find('(');
  if (open == std::string::npos) return f.text + " @" + std::to_string(f.node);
  const bool noArgs = f.text.compare(open, 2, "()") == 0;
  return f.text.substr(0, open + 1) + "@" + std::to_string(f.node) + (noArgs ? "" : ", ") +
         f.text.substr(open + 1);
}

std::string timeText(std::int64_t ns) {
  if (ns < 0) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, " at %.6f s", double(ns) / 1e9);
  return buf;
}

std::string how(const Derivation& d, NodeId node) {
  switch (d.kind) {
    case Derivation::Kind::Axiom:
      return "axiom " + (d.where.empty() ? std::string("(no source line)") : d.where);
    case Derivation::Kind::Sensed:
      return "sensed by the block" + timeText(d.time);
    case Derivation::Kind::Rule:
      break;
  }
  std::string s = "rule " + (d.where.empty() ? std::string("(no source line)") : d.where) + " at @" +
                  std::to_string(d.at);
  if (d.at != node) s += ", sent to @" + std::to_string(node) + " as a message";
  return s + timeText(d.time);
}

void collect(const DerivationLog& log, const FactAt& f, int depth, int maxDepth,
             std::set<std::pair<NodeId, std::string>>& path, std::vector<WhyLine>& out) {
  WhyLine line{depth, userForm(f), {}, {}};
  if (f.text.rfind("_init(", 0) == 0) {
    line.how = "start of the node";
    out.push_back(std::move(line));
    return;
  }
  const Derivation* d = log.find(f.node, f.text);
  if (!d) {
    line.how = "(no record: derived before recording started, or by the runtime)";
    out.push_back(std::move(line));
    return;
  }
  line.how = how(*d, f.node);
  line.where = d->kind == Derivation::Kind::Sensed ? std::string() : d->where;
  // Names meldc makes up (the reverse of a route, §6.7) are not in the program: say what they are.
  const std::size_t name = f.text[0] == '!' ? 1 : 0;
  if (f.text.compare(name, 3, "___") == 0)
    line.how += "  [made by meldc: a route fact reversed, for the rule that reaches a neighbour's facts]";
  out.push_back(std::move(line));
  if (depth + 1 > maxDepth) {
    out.push_back(WhyLine{depth + 1, "...", "(deeper than " + std::to_string(maxDepth) + " levels)", {}});
    return;
  }
  path.insert({f.node, f.text});
  for (const FactAt& p : d->premises) {
    if (path.count({p.node, p.text}))
      out.push_back(WhyLine{depth + 1, userForm(p), "(cycle: see above)", {}});
    else
      collect(log, p, depth + 1, maxDepth, path, out);
  }
  path.erase({f.node, f.text});
}

}  // namespace

std::string DerivationLog::key(NodeId node, const std::string& text) {
  std::string k = std::to_string(node);
  k += '\t';
  k += text;
  return k;
}

void DerivationLog::record(NodeId node, std::string text, Derivation d) {
  records_.try_emplace(key(node, text), std::move(d));
}

const Derivation* DerivationLog::find(NodeId node, const std::string& text) const {
  auto it = records_.find(key(node, text));
  return it == records_.end() ? nullptr : &it->second;
}

std::size_t DerivationLog::bytesInUse() const {
  std::size_t bytes = records_.bucket_count() * sizeof(void*);
  for (const auto& [k, d] : records_) {
    bytes += sizeof(std::pair<const std::string, Derivation>) + 2 * sizeof(void*) + k.capacity() +
             d.where.capacity() + d.rule.capacity() + d.premises.capacity() * sizeof(FactAt);
    for (const FactAt& p : d.premises) bytes += p.text.capacity();
  }
  return bytes;
}

FactAt parseFactSpec(const std::string& spec, const Program& program) {
  std::string s = squeeze(spec);
  if (!s.empty() && s[0] == '!') s.erase(0, 1);
  // `name(args)@N` (the simulator's form: FACT@BLOCK) is `name(@N, args)`.
  if (const auto at = s.rfind(")@"); at != std::string::npos && at + 2 < s.size()) {
    const std::string node = s.substr(at + 1), args = s.substr(s.find('(') + 1, at - s.find('(') - 1);
    s = s.substr(0, s.find('(') + 1) + node + (args.empty() ? "" : ",") + args + ")";
  }
  const auto open = s.find('(');
  if (open == std::string::npos || open == 0 || s.back() != ')')
    throw std::invalid_argument("'" + spec + "' is not a fact like name(@3, 1, 2)");
  const std::string name = s.substr(0, open);
  const PredId pred = program.predicates.find(name);  // case-insensitive, as Meld names (§1.3)
  if (pred >= program.predicates.size()) throw std::invalid_argument("the program has no predicate '" + name + "'");
  if (s.compare(open + 1, 1, "@") != 0)
    throw std::invalid_argument("'" + spec + "': the first argument is the node, like @3");
  std::size_t end = open + 2;
  while (end < s.size() && std::isdigit(static_cast<unsigned char>(s[end]))) ++end;
  if (end == open + 2) throw std::invalid_argument("'" + spec + "': @ must be followed by a node number");
  FactAt f;
  f.node = NodeId(std::stoul(s.substr(open + 2, end - open - 2)));
  const std::string rest = s[end] == ',' ? s.substr(end + 1) : s.substr(end);  // "1,2)" or ")"
  const PredicateDesc& d = program.predicates[pred];
  // The dump's spelling of the name, with ", " between arguments as the dump writes them.
  std::string args;
  bool quoted = false;
  for (const char c : rest) {
    if (c == '"') quoted = !quoted;
    args += c;
    if (c == ',' && !quoted) args += ' ';
  }
  f.text = (d.persistent() ? "!" : "") + d.name + "(" + args;
  return f;
}

std::vector<WhyLine> whyTree(const DerivationLog& log, const FactAt& fact, int maxDepth) {
  std::vector<WhyLine> out;
  if (!log.find(fact.node, fact.text)) return out;
  std::set<std::pair<NodeId, std::string>> path;
  collect(log, fact, 0, maxDepth, path, out);
  return out;
}

bool printWhy(std::ostream& out, const DerivationLog& log, const FactAt& fact, int maxDepth) {
  const std::vector<WhyLine> tree = whyTree(log, fact, maxDepth);
  for (const WhyLine& l : tree)
    out << std::string(std::size_t(l.depth) * 2, ' ') << l.fact << "    " << l.how << '\n';
  return !tree.empty();
}

}  // namespace meldvm
