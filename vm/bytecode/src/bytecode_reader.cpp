// `.mbc` bytes -> Program. Every read is bounds-checked against the enclosing section, every count
// is checked against the bytes left before anything is allocated for it, and the result goes
// through verifyProgram, so malformed input ends in a BytecodeError, never in a crash.
#include <bit>
#include <cstring>
#include <type_traits>

#include "file_bytes.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldvm {

namespace {

using namespace detail;

class Cursor {
 public:
  Cursor(const std::uint8_t* data, std::size_t size) : data_(data), end_(size) {}

  std::size_t pos() const { return pos_; }
  const std::uint8_t* data() const { return data_; }
  void skip(std::size_t bytes) { pos_ += bytes; }  // the caller checked that they are there
  std::size_t left() const { return end_ - pos_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw BytecodeError("bad bytecode: " + what + " at byte " + std::to_string(pos_), pos_);
  }
  void need(std::size_t n, const char* what) const {
    if (n > left())
      throw BytecodeError("truncated " + std::string(what) + " at byte " + std::to_string(pos_), pos_);
  }

  std::uint32_t word(const char* what) {
    need(4, what);
    const std::uint8_t* b = data_ + pos_;
    pos_ += 4;
    return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
           std::uint32_t(b[3]) << 24;
  }
  std::uint64_t u64(const char* what) {
    need(8, what);
    const std::uint64_t lo = word(what);
    return lo | std::uint64_t(word(what)) << 32;
  }
  double f64(const char* what) { return std::bit_cast<double>(u64(what)); }

  // A count of items that take at least `minBytes` each: one that cannot fit in what is left of the
  // section is refused here, so no caller ever sizes memory from an unchecked number.
  std::uint32_t count(const char* what, std::size_t minBytes) {
    const std::uint32_t n = word(what);
    if (n > left() / minBytes) {
      pos_ -= 4;
      fail(std::string(what) + " count " + std::to_string(n) + " exceeds the " + std::to_string(left()) +
           " bytes left");
    }
    return n;
  }
  // `n` words into `out`, an object of n plain 32-bit words (the caller checked they are there).
  template <class T>
  void copyWords(T* out, const char* what, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % 4 == 0 && alignof(T) <= 4);
    if constexpr (std::endian::native == std::endian::little) {
      if (n) std::memcpy(static_cast<void*>(out), data_ + pos_, n * 4);
      pos_ += n * 4;
    } else {
      std::uint32_t* w = reinterpret_cast<std::uint32_t*>(out);
      for (std::size_t i = 0; i < n; ++i) w[i] = word(what);
    }
  }
  // Appends a counted run of words to `out`.
  void appendWords(const char* what, std::vector<std::uint32_t>& out) {
    const std::uint32_t n = count(what, 4);
    const std::size_t from = out.size();
    out.resize(from + n);
    copyWords(out.data() + from, what, n);  // count() checked that the n words are there
  }
  std::vector<std::uint32_t> words(const char* what) {
    std::vector<std::uint32_t> v;
    appendWords(what, v);
    return v;
  }
  // A counted, zero-padded string, in place.
  std::string_view strView(const char* what) {
    const std::uint32_t n = count(what, 1);
    const std::size_t padded = (std::size_t(n) + 3) & ~std::size_t(3);
    need(padded, what);
    const std::string_view s(reinterpret_cast<const char*>(data_ + pos_), n);
    // Zero padding only, so that an accepted file is exactly what the writer makes of it.
    for (std::size_t i = n; i < padded; ++i)
      if (data_[pos_ + i] != 0) {
        pos_ += i;
        fail(std::string("non-zero padding after ") + what);
      }
    pos_ += padded;
    return s;
  }
  std::string str(const char* what) { return std::string(strView(what)); }
  CodeBlock block() {
    CodeBlock b;
    b.label = str("block label");
    b.registerTypes = words("register types");
    b.slots = word("slot count");
    b.code = words("code");
    return b;
  }
  // The next axiom block: into p.literalAxioms if it is literal facts only (no registers, no
  // slots, literalAxiomCode), otherwise into p.axiomBlocks. `code` is scratch.
  enum class AxiomKind : bool { General, Literal };
  AxiomKind axiomBlock(Program& p, std::vector<std::uint32_t>& code) {
    const std::size_t labelAt = pos_ + 4;
    const std::string_view label = strView("block label");
    std::vector<TypeId> registerTypes = words("register types");  // (none: no allocation)
    const std::uint32_t slots = word("slot count");
    if (p.literalAxioms.viewing() && registerTypes.empty() && slots == 0) {
      const std::size_t countAt = pos_;
      const std::uint32_t n = count("code", 4);
      if (literalAxiomCode({reinterpret_cast<const std::uint32_t*>(data_ + pos_), n})) {
        p.literalAxioms.addViewed(pos_, n, labelAt, std::uint32_t(label.size()));
        pos_ += std::size_t(n) * 4;
        return AxiomKind::Literal;
      }
      pos_ = countAt;  // a general block after all: read it again below
    }
    code.clear();
    appendWords("code", code);
    if (registerTypes.empty() && slots == 0 && literalAxiomCode(code)) {
      p.literalAxioms.add(code, label);
      return AxiomKind::Literal;
    }
    CodeBlock& b = p.axiomBlocks.emplace_back();
    b.label = label;
    b.registerTypes = std::move(registerTypes);
    b.slots = slots;
    b.code = code;
    return AxiomKind::General;
  }

  // Reads of a section stay within its declared length.
  std::size_t enter(std::size_t len) {
    const std::size_t outer = end_;
    end_ = pos_ + len;
    return outer;
  }
  void leave(std::size_t outer, const char* section) {
    if (pos_ != end_) fail(std::to_string(left()) + " unread bytes at the end of section " + section);
    end_ = outer;
  }

 private:
  const std::uint8_t* data_;
  std::size_t pos_ = 0;
  std::size_t end_;
};

void readTypes(Cursor& c, TypeTable& types) {
  const std::uint32_t n = c.count("type", 4);
  if (n < types.size())
    c.fail("type count " + std::to_string(n) + " below the " + std::to_string(types.size()) +
           " built-in types");
  for (TypeId t = 0; t < n; ++t) {
    const std::uint32_t kind = c.word("type kind");
    if (t < types.size() && kind != std::uint32_t(types.kind(t)))
      c.fail("built-in type " + std::to_string(t) + " has kind " + std::to_string(kind));
    if (t < types.size()) continue;
    // Types refer only to earlier ids (the writer writes in id order, interning creates them so).
    const auto ref = [&](const char* what) {
      const std::uint32_t e = c.word(what);
      if (e >= t)
        c.fail("type " + std::to_string(t) + " refers to type " + std::to_string(e) +
               " not defined before it");
      return e;
    };
    TypeId got;
    switch (kind) {
      case std::uint32_t(TypeKind::List):
        got = types.list(ref("list element type"));
        break;
      case std::uint32_t(TypeKind::Array):
        got = types.array(ref("array element type"));
        break;
      case std::uint32_t(TypeKind::Set):
        got = types.set(ref("set element type"));
        break;
      case std::uint32_t(TypeKind::Struct): {
        const std::uint32_t fc = c.count("struct field", 4);
        std::vector<TypeId> fields;
        fields.reserve(fc);
        for (std::uint32_t i = 0; i < fc; ++i) fields.push_back(ref("struct field type"));
        got = types.structOf(fields);
        break;
      }
      default:
        c.fail("type " + std::to_string(t) + " has kind " + std::to_string(kind) +
               " (not list, array, set or struct)");
    }
    if (got != t) c.fail("type " + std::to_string(t) + " duplicates type " + std::to_string(got));
  }
}

void readPredicates(Cursor& c, Program& p) {
  const std::uint32_t n = c.count("predicate", 4 * 5);
  for (std::uint32_t i = 0; i < n; ++i) {
    PredicateDesc d;
    d.name = c.str("predicate name");
    d.fields = c.words("predicate fields");
    for (TypeId t : d.fields)
      if (t >= p.types.size()) c.fail("predicate " + d.name + " has unknown field type " + std::to_string(t));
    const std::uint32_t flags = c.word("predicate flags");
    if (flags & ~kPredFlagsAll) c.fail("predicate " + d.name + " has unknown flag bits");
    d.linear = flags & kPredLinear;
    d.route = flags & kPredRoute;
    d.reverseRoute = flags & kPredReverseRoute;
    d.action = flags & kPredAction;
    d.thread = flags & kPredThread;
    d.compact = flags & kPredCompact;
    const std::uint32_t agg = c.word("aggregate kind");
    if (agg > std::uint32_t(AggregateKind::Sum))
      c.fail("predicate " + d.name + " has unknown aggregate kind");
    d.aggregate = AggregateKind(agg);
    d.aggregateField = c.word("aggregate field");
    try {
      p.predicates.add(std::move(d));
    } catch (const std::exception& e) {
      c.fail(e.what());
    }
  }
  p.initPredicate = c.word("init predicate");
}

// What one section leaves for a later one.
struct ReadState {
  // The axiom blocks in file order: general (Program::axiomBlocks) or literal, each kind in order.
  std::vector<Cursor::AxiomKind> axiomKinds;
};

// Checked here, not by the verifier: a wrong line only misleads a message, but it is refused.
void checkLines(const Cursor& c, std::span<const SourceLine> lines, std::size_t files, std::size_t codeSize,
                std::string_view label) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const SourceLine& l = lines[i];
    if (l.pc >= codeSize || l.file >= files || (i && l.pc <= lines[i - 1].pc))
      c.fail("source line " + std::to_string(i) + " of block '" + std::string(label) +
             "' is out of order or out of range");
  }
}

// A block's source lines, appended to `out`.
void readLines(Cursor& c, std::size_t files, std::size_t codeSize, std::string_view label,
               std::vector<SourceLine>& out) {
  const std::uint32_t n = c.count("source line", 12);
  const std::size_t from = out.size();
  out.resize(from + n);
  c.copyWords(out.data() + from, "source line", std::size_t(n) * 3);  // count() checked they are there
  checkLines(c, std::span<const SourceLine>(out).subspan(from), files, codeSize, label);
}

// The source lines of literal axiom block i, viewed in place or copied.
void readLiteralLines(Cursor& c, std::size_t files, LiteralAxioms& axioms, std::size_t i,
                      std::vector<SourceLine>& scratch) {
  if (!axioms.viewing()) {
    scratch.clear();
    readLines(c, files, axioms.code(i).size(), axioms.label(i), scratch);
    axioms.addLines(scratch);
    return;
  }
  const std::uint32_t n = c.count("source line", 12);
  const std::size_t at = c.pos();
  c.skip(std::size_t(n) * 12);  // count() checked they are there
  checkLines(c, {reinterpret_cast<const SourceLine*>(c.data() + at), n}, files, axioms.code(i).size(),
             axioms.label(i));
  axioms.addLinesViewed(at, n);
}

void readAxioms(Cursor& c, Program& p, ReadState& st) {
  p.nodeAxioms = c.words("node axioms");
  const std::uint32_t n = c.count("axiom block", 4 * 4);
  st.axiomKinds.reserve(n);
  p.literalAxioms.reserveBlocks(n);  // a bound: general blocks take none
  if (!p.literalAxioms.viewing()) p.literalAxioms.reserveCode(c.left() / 4);
  std::vector<std::uint32_t> code;
  for (std::uint32_t i = 0; i < n; ++i) st.axiomKinds.push_back(c.axiomBlock(p, code));
  // Blocks are numbered axiomBlocks first, then literalAxioms: renumber the nodes' blocks.
  std::vector<std::uint32_t> number(n);
  std::uint32_t general = 0, literal = std::uint32_t(p.axiomBlocks.size());
  for (std::uint32_t i = 0; i < n; ++i)
    number[i] = st.axiomKinds[i] == Cursor::AxiomKind::General ? general++ : literal++;
  for (std::uint32_t& b : p.nodeAxioms)
    if (b < n) b = number[b];  // others stay out of range for the verifier to refuse
}

void readSources(Cursor& c, Program& p, const ReadState& st) {
  const std::uint32_t files = c.count("source file", 4);
  for (std::uint32_t i = 0; i < files; ++i) p.sourceFiles.push_back(c.str("source file name"));
  forEachCodeBlockBeforeAxioms(p,
                               [&](CodeBlock& b) { readLines(c, files, b.code.size(), b.label, b.lines); });
  std::size_t general = 0, literal = 0;
  if (!p.literalAxioms.empty() && !p.literalAxioms.viewing())
    p.literalAxioms.reserveLines(c.left() / sizeof(SourceLine));
  std::vector<SourceLine> scratch;
  for (const Cursor::AxiomKind kind : st.axiomKinds) {
    if (kind == Cursor::AxiomKind::General) {
      CodeBlock& b = p.axiomBlocks[general++];
      readLines(c, files, b.code.size(), b.label, b.lines);
      continue;
    }
    readLiteralLines(c, files, p.literalAxioms, literal++, scratch);
  }
}

void readSection(Cursor& c, std::uint32_t tag, Program& p, ReadState& st) {
  switch (tag) {
    case kSecTypes:
      readTypes(c, p.types);
      break;
    case kSecPredicates:
      readPredicates(c, p);
      break;
    case kSecNodes: {
      const std::uint32_t n = c.count("node", 8);
      p.nodeSourceIds.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) p.nodeSourceIds.push_back(std::int64_t(c.u64("node source id")));
      break;
    }
    case kSecStrings: {
      const std::uint32_t n = c.count("string", 4);
      p.strings.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) p.strings.push_back(c.str("string constant"));
      break;
    }
    case kSecGlobals: {
      const std::uint32_t n = c.count("global", 8);
      p.globals.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        Global g;
        g.name = c.str("global name");
        g.type = c.word("global type");
        p.globals.push_back(std::move(g));
      }
      p.globalsInit = c.block();
      break;
    }
    case kSecFunctions: {
      const std::uint32_t n = c.count("function", 4 * 7);
      p.functions.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        Function f;
        f.name = c.str("function name");
        f.params = c.words("function parameters");
        f.result = c.word("function result type");
        f.block = c.block();
        p.functions.push_back(std::move(f));
      }
      break;
    }
    case kSecExterns: {
      const std::uint32_t n = c.count("extern", 4 * 3);
      p.externs.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        Extern e;
        e.name = c.str("extern name");
        e.params = c.words("extern parameters");
        e.result = c.word("extern result type");
        p.externs.push_back(std::move(e));
      }
      break;
    }
    case kSecRules: {
      const std::uint32_t n = c.count("rule", 4 * 5);
      p.rules.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        Rule r;
        r.block = c.block();
        r.bodyPredicates = c.words("body predicates");
        p.rules.push_back(std::move(r));
      }
      break;
    }
    case kSecProcesses: {
      const std::uint32_t n = c.count("process", 4 * 5);
      p.processes.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        Process pr;
        pr.trigger = c.word("process trigger");
        pr.block = c.block();
        p.processes.push_back(std::move(pr));
      }
      break;
    }
    case kSecAxioms:
      readAxioms(c, p, st);
      break;
    case kSecScheduling: {
      SchedulingOptions& o = p.scheduling;
      const std::uint32_t order = c.word("priority order");
      if (order > std::uint32_t(PriorityOrder::Asc))
        c.fail("unknown priority order " + std::to_string(order));
      o.order = PriorityOrder(order);
      const std::uint32_t flags = c.word("scheduling flags");
      if (flags & ~kSchedFlagsAll) c.fail("unknown scheduling flag bits");
      o.hasInitialPriority = flags & kSchedInitial;
      o.hasDefaultPriority = flags & kSchedDefault;
      o.noInitialPriorities = flags & kSchedNoInitial;
      o.staticNodes = flags & kSchedStatic;
      o.initialPriority = c.f64("initial priority");
      o.defaultPriority = c.f64("default priority");
      o.hasNoPriority = flags & kSchedNoPriority;
      if (o.hasNoPriority) o.noPriority = c.f64("no-priority value");
      break;
    }
    case kSecIndexes: {
      const std::uint32_t n = c.count("index", 8);
      p.indexes.reserve(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        IndexRequest ix;
        ix.predicate = c.word("index predicate");
        ix.field = c.word("index field");
        p.indexes.push_back(ix);
      }
      p.highestArg = c.word("highest argument");
      break;
    }
    case kSecSources:
      readSources(c, p, st);
      break;
  }
}

// owner: null to copy the literal axioms, else the keeper of `data` for viewing them in place.
std::unique_ptr<Program> parse(const std::uint8_t* data, std::size_t size,
                               std::shared_ptr<const void>* owner) {
  Cursor c(data, size);
  c.need(4, "magic");
  if (std::memcmp(data, kMagic, 4) != 0) c.fail("not a Meld bytecode file (magic is not MBC1)");
  c.word("magic");
  const std::uint32_t version = c.word("version");
  if (version < kOldestBytecodeVersion || version > kBytecodeVersion)
    c.fail("bytecode version " + std::to_string(version) + " is not supported (this VM reads versions " +
           std::to_string(kOldestBytecodeVersion) + " to " + std::to_string(kBytecodeVersion) + ")");
  const std::uint32_t sections = c.word("section count"), expected = sectionCountOf(version);
  if (sections != expected)
    c.fail("section count " + std::to_string(sections) + " (expected " + std::to_string(expected) + ")");

  auto p = std::make_unique<Program>();
  // In place only where the words can be read as they lie: aligned, in the file's byte order.
  if (owner && std::endian::native == std::endian::little && reinterpret_cast<std::uintptr_t>(data) % 4 == 0)
    p->literalAxioms.view(data, std::move(*owner));
  ReadState st;
  for (std::uint32_t want = 1; want <= expected; ++want) {
    const std::uint32_t tag = c.word("section tag");
    if (tag == 0 || tag > expected) c.fail("unknown section tag " + std::to_string(tag));
    if (tag != want)
      c.fail(std::string("section ") + sectionName(tag) + " out of order (expected section " +
             sectionName(want) + ")");
    const std::uint32_t len = c.word("section length");
    if (len % 4 != 0) c.fail(std::string("section ") + sectionName(tag) + " length is not a multiple of 4");
    c.need(len, sectionName(tag));
    const std::size_t outer = c.enter(len);
    readSection(c, tag, *p, st);
    c.leave(outer, sectionName(tag));
  }
  if (c.left() != 0) c.fail(std::to_string(c.left()) + " bytes of trailing garbage after the last section");
  // Nothing viewed: the bytes (a file's mapping, which counts in the run's memory) go now.
  if (p->literalAxioms.viewing() && p->literalAxioms.empty()) p->literalAxioms = LiteralAxioms();
  verifyProgram(*p);
  return p;
}

}  // namespace

std::unique_ptr<Program> readBytecode(const std::uint8_t* data, std::size_t size) {
  return parse(data, size, nullptr);
}

std::unique_ptr<Program> readBytecodeInPlace(const std::uint8_t* data, std::size_t size,
                                             std::shared_ptr<const void> owner) {
  return parse(data, size, &owner);
}

std::unique_ptr<Program> readBytecodeFile(const std::string& path) {
  auto bytes = std::make_shared<const detail::FileBytes>(path);
  try {
    return readBytecodeInPlace(bytes->data(), bytes->size(), bytes);
  } catch (const BytecodeError& e) {
    throw BytecodeError(path + ": " + e.what(), e.offset());
  }
}

}  // namespace meldvm
