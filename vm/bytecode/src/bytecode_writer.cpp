// Program -> `.mbc` bytes (layout in bytecode.hpp). The writer trusts the Program: meldc builds it
// and the reader verifies what comes back.
#include <bit>

#include "meldvm/bytecode.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldvm {

namespace {

using namespace detail;

class Writer {
 public:
  std::vector<std::uint8_t> bytes;

  void word(std::uint32_t w) {
    for (int i = 0; i < 4; ++i) bytes.push_back(std::uint8_t(w >> (8 * i)));
  }
  // Low word first, like the D operand of opcodes.def.
  void u64(std::uint64_t v) {
    word(std::uint32_t(v));
    word(std::uint32_t(v >> 32));
  }
  void f64(double d) { u64(std::bit_cast<std::uint64_t>(d)); }  // bit-exact, NaN payloads included
  void str(std::string_view s) {
    word(std::uint32_t(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
    while (bytes.size() % 4 != 0) bytes.push_back(0);
  }
  void words(std::span<const std::uint32_t> v) {
    word(std::uint32_t(v.size()));
    for (std::uint32_t w : v) word(w);
  }
  void block(const CodeBlock& b) {
    str(b.label);
    words(b.registerTypes);
    word(b.slots);
    words(b.code);
  }

  // Sections carry their byte length so that the reader can bound every read to the section.
  std::size_t begin(SectionTag tag) {
    word(tag);
    word(0);
    return bytes.size();
  }
  void end(std::size_t start) {
    const auto len = std::uint32_t(bytes.size() - start);
    for (int i = 0; i < 4; ++i) bytes[start - 4 + i] = std::uint8_t(len >> (8 * i));
  }
};

// The order the axiom blocks are written in: the reader keeps a block whose code is only literal
// facts (literalAxiomCode) as a literal axiom, numbered after the others, so the file has them
// there too, or reading it back and writing it again would give other bytes (meldc's axiom blocks
// are all CodeBlocks, literal ones among the others). order[k]: the block written k-th;
// number[b]: where block b (axiomBlocks, then literalAxioms) is written.
struct AxiomOrder {
  std::vector<std::uint32_t> order, number;
  explicit AxiomOrder(const Program& p) {
    const auto blocks = std::uint32_t(p.axiomBlocks.size());
    auto literal = [&](std::uint32_t b) {
      const CodeBlock& c = p.axiomBlocks[b];
      return c.registerTypes.empty() && c.slots == 0 && literalAxiomCode(c.code);
    };
    for (std::uint32_t b = 0; b < blocks; ++b)
      if (!literal(b)) order.push_back(b);
    for (std::uint32_t b = 0; b < blocks; ++b)
      if (literal(b)) order.push_back(b);
    for (std::uint32_t i = 0; i < p.literalAxioms.size(); ++i) order.push_back(blocks + i);
    number.resize(order.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) number[order[k]] = k;
  }
};

void writeTypes(Writer& w, const TypeTable& types) {
  // In id order, each type after the ones it refers to, so the reader can re-intern them and get
  // the same ids.
  w.word(std::uint32_t(types.size()));
  for (TypeId t = 0; t < types.size(); ++t) {
    const TypeKind k = types.kind(t);
    w.word(std::uint32_t(k));
    if (k == TypeKind::List || k == TypeKind::Array || k == TypeKind::Set) {
      w.word(types.element(t));
    } else if (k == TypeKind::Struct) {
      const auto fields = types.fields(t);
      w.word(std::uint32_t(fields.size()));
      for (TypeId f : fields) w.word(f);
    }
  }
}

void writePredicates(Writer& w, const Program& p) {
  w.word(std::uint32_t(p.predicates.size()));
  for (PredId id = 0; id < p.predicates.size(); ++id) {
    const PredicateDesc& d = p.predicates[id];
    w.str(d.name);
    w.words(d.fields);
    w.word((d.linear ? kPredLinear : 0) | (d.route ? kPredRoute : 0) |
           (d.reverseRoute ? kPredReverseRoute : 0) | (d.action ? kPredAction : 0) |
           (d.thread ? kPredThread : 0) | (d.compact ? kPredCompact : 0));
    w.word(std::uint32_t(d.aggregate));
    w.word(d.aggregateField);
  }
  w.word(p.initPredicate);
}

}  // namespace

std::vector<std::uint8_t> writeBytecode(const Program& p) {
  Writer w;
  const AxiomOrder axioms(p);
  const auto blocks = std::uint32_t(p.axiomBlocks.size());
  // Byte by byte: GCC 12 warns of a bogus overflow for a range insert into the empty vector.
  for (const char ch : kMagic) w.bytes.push_back(std::uint8_t(ch));
  w.word(kBytecodeVersion);
  w.word(sectionCountOf(kBytecodeVersion));

  std::size_t s = w.begin(kSecTypes);
  writeTypes(w, p.types);
  w.end(s);

  s = w.begin(kSecPredicates);
  writePredicates(w, p);
  w.end(s);

  s = w.begin(kSecNodes);
  w.word(std::uint32_t(p.nodeSourceIds.size()));
  for (std::int64_t id : p.nodeSourceIds) w.u64(std::uint64_t(id));
  w.end(s);

  s = w.begin(kSecStrings);
  w.word(std::uint32_t(p.strings.size()));
  for (const std::string& str : p.strings) w.str(str);
  w.end(s);

  s = w.begin(kSecGlobals);
  w.word(std::uint32_t(p.globals.size()));
  for (const Global& g : p.globals) {
    w.str(g.name);
    w.word(g.type);
  }
  w.block(p.globalsInit);
  w.end(s);

  s = w.begin(kSecFunctions);
  w.word(std::uint32_t(p.functions.size()));
  for (const Function& f : p.functions) {
    w.str(f.name);
    w.words(f.params);
    w.word(f.result);
    w.block(f.block);
  }
  w.end(s);

  s = w.begin(kSecExterns);
  w.word(std::uint32_t(p.externs.size()));
  for (const Extern& e : p.externs) {
    w.str(e.name);
    w.words(e.params);
    w.word(e.result);
  }
  w.end(s);

  s = w.begin(kSecRules);
  w.word(std::uint32_t(p.rules.size()));
  for (const Rule& r : p.rules) {
    w.block(r.block);
    w.words(r.bodyPredicates);
  }
  w.end(s);

  s = w.begin(kSecProcesses);
  w.word(std::uint32_t(p.processes.size()));
  for (const Process& pr : p.processes) {
    w.word(pr.trigger);
    w.block(pr.block);
  }
  w.end(s);

  s = w.begin(kSecAxioms);
  w.word(std::uint32_t(p.nodeAxioms.size()));
  for (const std::uint32_t b : p.nodeAxioms) w.word(b < axioms.number.size() ? axioms.number[b] : b);
  w.word(std::uint32_t(p.axiomBlockCount()));
  for (const std::uint32_t b : axioms.order) {
    if (b < blocks) {
      w.block(p.axiomBlocks[b]);
      continue;
    }
    w.str(p.literalAxioms.label(b - blocks));
    w.word(0);  // no registers
    w.word(0);  // no slots
    w.words(p.literalAxioms.code(b - blocks));
  }
  w.end(s);

  s = w.begin(kSecScheduling);
  const SchedulingOptions& o = p.scheduling;
  w.word(std::uint32_t(o.order));
  w.word((o.hasInitialPriority ? kSchedInitial : 0) | (o.hasDefaultPriority ? kSchedDefault : 0) |
         (o.noInitialPriorities ? kSchedNoInitial : 0) | (o.staticNodes ? kSchedStatic : 0) |
         (o.hasNoPriority ? kSchedNoPriority : 0));
  w.f64(o.initialPriority);
  w.f64(o.defaultPriority);
  if (o.hasNoPriority) w.f64(o.noPriority);
  w.end(s);

  s = w.begin(kSecIndexes);
  w.word(std::uint32_t(p.indexes.size()));
  for (const IndexRequest& ix : p.indexes) {
    w.word(ix.predicate);
    w.word(ix.field);
  }
  w.word(p.highestArg);
  w.end(s);

  s = w.begin(kSecSources);
  w.word(std::uint32_t(p.sourceFiles.size()));
  for (const std::string& f : p.sourceFiles) w.str(f);
  const auto lines = [&](std::span<const SourceLine> ls) {
    w.word(std::uint32_t(ls.size()));
    for (const SourceLine& l : ls) {
      w.word(l.pc);
      w.word(l.file);
      w.word(l.line);
    }
  };
  forEachCodeBlockBeforeAxioms(p, [&](const CodeBlock& b) { lines(b.lines); });
  for (const std::uint32_t b : axioms.order)
    lines(b < blocks ? std::span<const SourceLine>(p.axiomBlocks[b].lines)
                     : p.literalAxioms.lines(b - blocks));
  w.end(s);

  return std::move(w.bytes);
}

}  // namespace meldvm
