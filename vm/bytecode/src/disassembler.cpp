// The `meldc --emit=asm` listing. Robust on unverified programs too (out-of-range operands print as
// numbers with '?'), since it is also how one looks at a file the verifier refuses.
#include <cinttypes>
#include <cstdio>
#include <ostream>

#include "meldvm/builtin_signatures.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldvm {

namespace {

using detail::typeName;

std::string word4(std::size_t n) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%04zu", n);
  return buf;
}

// prefix + number, built by appending: GCC 12 -O3 warns falsely (-Wrestrict) on "literal" + string.
std::string tagged(const char* prefix, std::uint64_t v) {
  std::string s = prefix;
  s += std::to_string(v);
  return s;
}
std::string unknown(std::uint32_t v) { return tagged("?", v); }

std::string number(double d) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", d);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += char(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += char(c);
    }
  }
  return out + "\"";
}

class Lister {
 public:
  Lister(const Program& p, std::ostream& out) : p_(p), out_(out) {}

  void header();
  void block(const std::string& title, const CodeBlock& b);

 private:
  std::string type(TypeId t) const { return t < p_.types.size() ? typeName(p_.types, t) : unknown(t); }
  std::string pred(PredId id) const {
    if (id >= p_.predicates.size()) return unknown(id);
    return p_.predicates[id].name + "(" + std::to_string(p_.predicates[id].arity()) + ")";
  }
  std::string typeList(const std::vector<TypeId>& ts) const {
    std::string s;
    for (std::size_t i = 0; i < ts.size(); ++i) s += (i ? ", " : "") + type(ts[i]);
    return s;
  }
  std::string predFlags(const PredicateDesc& d) const;
  std::string iterFlags(std::uint32_t f) const;
  std::string operand(Opcode op, char letter, std::span<const std::uint32_t> code, std::size_t w) const;
  std::string axiomFacts(PredId pred, std::span<const std::uint32_t> data) const;

  const Program& p_;
  std::ostream& out_;
};

std::string Lister::predFlags(const PredicateDesc& d) const {
  static constexpr const char* kAgg[] = {"", "first", "min", "max", "sum"};
  std::string s = d.linear ? "linear" : "persistent";
  if (d.route) s += " route";
  if (d.reverseRoute) s += " reverse-route";
  if (d.action) s += " action";
  if (d.thread) s += " thread";
  if (d.compact) s += " compact";
  if (d.aggregated() && std::size_t(d.aggregate) < std::size(kAgg))
    s += std::string(" aggregate ") + kAgg[std::size_t(d.aggregate)] + " field " +
         std::to_string(d.aggregateField);
  return s;
}

// The facts of AXIOM_FACTS, one per line; the raw words where they do not decode.
std::string Lister::axiomFacts(PredId pred, std::span<const std::uint32_t> data) const {
  const std::size_t per =
      pred < p_.predicates.size() ? detail::axiomFactWords(p_.predicates[pred].fields) : 0;
  std::string s = " ";
  s.append(std::to_string(per ? data.size() / per : 0)).append(" facts");
  if (per == 0 || data.size() % per != 0) {
    s += ", data words";
    for (const std::uint32_t w : data) s.append(" ").append(std::to_string(w));
    return s;
  }
  for (const std::uint32_t* w = data.data(); w != data.data() + data.size();) {
    s += "\n                 (";
    bool first = true;
    for (const TypeId t : p_.predicates[pred].fields) {
      const Value v = detail::axiomField(t, w);
      s += first ? "" : ", ";
      first = false;
      if (t == TypeTable::kFloat)
        s += number(v.asFloat());
      else if (t == TypeTable::kNode)
        s.append("@").append(std::to_string(v.asNode()));
      else if (t == TypeTable::kBool)
        s += v.asBool() ? "true" : "false";
      else
        s += std::to_string(v.asInt());
    }
    s += ")";
  }
  return s;
}

std::string Lister::iterFlags(std::uint32_t f) const {
  static constexpr const char* kNames[] = {"linear", "consume",          "return-on-fire",
                                           "random", "consumable-class", "thread"};
  if (f == 0) return "0";
  std::string s;
  for (std::uint32_t bit = 0; bit < 32; ++bit) {
    if (!(f & (1u << bit))) continue;
    if (!s.empty()) s += "|";
    s += bit < std::size(kNames) ? kNames[bit] : "bit" + std::to_string(bit);
  }
  return s;
}

std::string Lister::operand(Opcode op, char letter, std::span<const std::uint32_t> code,
                            std::size_t w) const {
  const std::uint32_t v = code[w];
  const auto indexed = [&](const char* key, std::size_t size, auto name) {
    return std::string(key) + "=" + (v < size ? name() : unknown(v));
  };
  switch (letter) {
    case 'r':
    case 'i':
    case 'f':
    case 'b':
    case 'n':
    case 'l':
    case 's':
      return tagged("r", v);
    case 'S':
      return tagged("s=", v);
    case 'P':
      return "p=" + pred(v);
    case 'T':
      return "t=<" + type(v) + ">";
    case 'K':
      return indexed("k", p_.strings.size(), [&] { return quoted(p_.strings[v]); });
    case 'G':
      return indexed("g", p_.globals.size(), [&] { return p_.globals[v].name; });
    case 'U':
      return indexed("fn", p_.functions.size(), [&] { return p_.functions[v].name; });
    case 'E':
      return indexed("ext", p_.externs.size(), [&] { return p_.externs[v].name; });
    case 'B': {
      const BuiltinInfo* b = v < kBuiltinIdCount ? findBuiltin(std::uint16_t(v)) : nullptr;
      return "b=" + (b ? std::string(b->name) : unknown(v));
    }
    case 'I':
      return std::to_string(std::int32_t(v));
    case 'D':
      return number(std::bit_cast<double>(std::uint64_t(v) | std::uint64_t(code[w + 1]) << 32));
    case 'F':
      return tagged("f=", v);
    case 'X':
      if (op == Opcode::UPDATE)
        return v == kUpdateMoveToBack ? "flags=move-to-back" : "flags=" + std::to_string(v);
      return "flags=" + iterFlags(v);
    case 'J':
      return "j=" + word4(v);
    default:
      return "?";
  }
}

void Lister::block(const std::string& title, const CodeBlock& b) {
  out_ << "\n" << title << "\n";
  out_ << "  registers:" << (b.registerTypes.empty() ? " none" : "");
  for (std::size_t r = 0; r < b.registerTypes.size(); ++r)
    out_ << (r ? ", r" : " r") << r << " " << type(b.registerTypes[r]);
  out_ << "\n  slots: " << b.slots << "\n";
  const std::span<const std::uint32_t> code = b.code;
  for (std::size_t pos = 0; pos < code.size();) {
    std::string why;
    const std::size_t len = detail::instructionLength(code, pos, why);
    if (len == 0) {
      out_ << "  " << word4(pos) << "  ?? " << why << "\n";
      return;
    }
    const auto op = Opcode(code[pos]);
    const OpcodeInfo& info = opcodeInfo(op);
    char name[32];
    std::snprintf(name, sizeof name, "%-9s", info.name);
    std::string line = "  " + word4(pos) + "  " + name;
    std::size_t w = pos + 1;
    for (const char* l = info.operands; *l; ++l) {
      if (*l == 'W') {
        line += axiomFacts(code[pos + 1], code.subspan(w + 1, code[w]));
        break;
      }
      if (*l == '*') {
        line += " (";
        for (std::uint32_t i = 0; i < code[w]; ++i)
          line += (i ? ", r" : "r") + std::to_string(code[w + 1 + i]);
        line += ")";
        break;
      }
      line += ' ';
      line += operand(op, *l, code, w);
      w += *l == 'D' ? 2 : 1;
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out_ << line << "\n";
    pos += len;
  }
}

void Lister::header() {
  out_ << "; Meld bytecode version " << kBytecodeVersion << "\n";
  out_ << "\ntypes:\n";
  for (TypeId t = 0; t < p_.types.size(); ++t) out_ << "  " << t << "  " << type(t) << "\n";
  out_ << "\npredicates:\n";
  for (PredId id = 0; id < p_.predicates.size(); ++id) {
    const PredicateDesc& d = p_.predicates[id];
    out_ << "  " << id << "  " << d.name << "(" << typeList(d.fields) << ") " << predFlags(d)
         << (id == p_.initPredicate ? " init" : "") << "\n";
  }
  out_ << "\nnodes:\n";
  for (std::size_t n = 0; n < p_.nodeSourceIds.size(); ++n) {
    out_ << "  " << n << " -> @" << p_.nodeSourceIds[n];
    if (n < p_.nodeAxioms.size() && p_.nodeAxioms[n] != Program::kNoAxioms)
      out_ << "  axioms " << p_.nodeAxioms[n];
    out_ << "\n";
  }
  if (!p_.strings.empty()) out_ << "\nstrings:\n";
  for (std::size_t i = 0; i < p_.strings.size(); ++i)
    out_ << "  " << i << "  " << quoted(p_.strings[i]) << "\n";
  if (!p_.globals.empty()) out_ << "\nglobals:\n";
  for (std::size_t i = 0; i < p_.globals.size(); ++i)
    out_ << "  " << i << "  " << p_.globals[i].name << " : " << type(p_.globals[i].type) << "\n";
  if (!p_.externs.empty()) out_ << "\nexterns:\n";
  for (std::size_t i = 0; i < p_.externs.size(); ++i) {
    const Extern& e = p_.externs[i];
    out_ << "  " << i << "  " << e.name << "(" << typeList(e.params) << ") : " << type(e.result) << "\n";
  }
  const SchedulingOptions& o = p_.scheduling;
  out_ << "\nscheduling: " << (o.order == PriorityOrder::Asc ? "asc" : "desc");
  if (o.hasInitialPriority) out_ << ", initial " << number(o.initialPriority);
  if (o.hasDefaultPriority) out_ << ", default " << number(o.defaultPriority);
  if (o.noInitialPriorities) out_ << ", no-initial-priorities";
  if (o.hasNoPriority) out_ << ", no-priority " << number(o.noPriority);
  if (o.staticNodes) out_ << ", static";
  out_ << "\n";
  for (const IndexRequest& ix : p_.indexes)
    out_ << "index: " << pred(ix.predicate) << " field " << ix.field << "\n";
  if (p_.highestArg) out_ << "highest @arg: " << p_.highestArg << "\n";
}

}  // namespace

void disassemble(const Program& p, std::ostream& out) {
  Lister l(p, out);
  l.header();
  l.block("globals", p.globalsInit);
  for (std::size_t i = 0; i < p.functions.size(); ++i) {
    const Function& f = p.functions[i];
    std::string params;
    for (std::size_t k = 0; k < f.params.size(); ++k)
      params += (k ? ", " : "") + (f.params[k] < p.types.size() ? typeName(p.types, f.params[k]) : "?");
    l.block("function " + std::to_string(i) + ": " + f.name + "(" + params +
                ") : " + (f.result < p.types.size() ? typeName(p.types, f.result) : "?"),
            f.block);
  }
  for (std::size_t i = 0; i < p.rules.size(); ++i) {
    std::string body;
    for (PredId b : p.rules[i].bodyPredicates)
      body += (body.empty() ? "" : ", ") + (b < p.predicates.size() ? p.predicates[b].name : unknown(b));
    l.block("rule " + std::to_string(i) + ": " + p.rules[i].block.label + "\n  body: " + body,
            p.rules[i].block);
  }
  for (const Process& pr : p.processes) {
    const std::string on = pr.trigger < p.predicates.size() ? p.predicates[pr.trigger].name : "?";
    l.block("process on " + on + ": " + pr.block.label, pr.block);
  }
  for (std::size_t i = 0; i < p.axiomBlockCount(); ++i) {
    std::string nodes;
    for (std::size_t n = 0; n < p.nodeAxioms.size(); ++n)
      if (p.nodeAxioms[n] == i) {
        if (!nodes.empty()) nodes += ' ';
        nodes += std::to_string(n);
      }
    l.block("axioms " + std::to_string(i) + " of node" + (nodes.find(' ') != std::string::npos ? "s " : " ") +
                nodes,
            i < p.axiomBlocks.size() ? p.axiomBlocks[i] : p.literalAxioms.block(i - p.axiomBlocks.size()));
  }
}

}  // namespace meldvm
