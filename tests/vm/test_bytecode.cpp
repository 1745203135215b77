// The `.mbc` writer and reader: exact round trips, the disassembly, and malformed input (every
// truncation, byte flips, random word changes) ending in BytecodeError rather than a crash.
#define BOOST_TEST_MODULE vm_bytecode
#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "bytecode_fixture.hpp"

using namespace bctest;

namespace {

std::string listing(const Program& p) {
  std::ostringstream out;
  disassemble(p, out);
  return out.str();
}

// The reader's message for these bytes, or "" when it accepts them. An accepted input must also
// write back to the same bytes and disassemble.
std::string readError(const std::vector<std::uint8_t>& bytes) {
  try {
    const auto p = readBytecode(bytes.data(), bytes.size());
    BOOST_TEST((writeBytecode(*p) == bytes));
    (void)listing(*p);
  } catch (const BytecodeError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

void put(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t w) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = std::uint8_t(w >> (8 * i));
}

std::uint32_t get(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint32_t w = 0;
  for (int i = 0; i < 4; ++i) w |= std::uint32_t(bytes[at + i]) << (8 * i);
  return w;
}

// The same file as an older version writes it: without the sources section (the last one).
std::vector<std::uint8_t> asVersion(std::vector<std::uint8_t> bytes, std::uint32_t version) {
  std::size_t at = 12;
  while (get(bytes, at) != 13) at += 8 + get(bytes, at + 4);
  bytes.resize(at);
  put(bytes, 4, version);
  put(bytes, 8, 12);
  return bytes;
}

}  // namespace

BOOST_AUTO_TEST_CASE(round_trip_is_exact) {
  for (const auto& make : {smallProgram, fullProgram}) {
    const auto p = make();
    BOOST_REQUIRE_EQUAL(verifyError(*p), "");
    const auto bytes = writeBytecode(*p);
    BOOST_TEST(bytes.size() % 4 == 0);
    const auto q = readBytecode(bytes.data(), bytes.size());
    BOOST_TEST((writeBytecode(*q) == bytes));
    BOOST_TEST(listing(*q) == listing(*p));
    BOOST_TEST(q->types.size() == p->types.size());
    BOOST_TEST(q->predicates.size() == p->predicates.size());
  }
}

BOOST_AUTO_TEST_CASE(round_trip_keeps_values) {
  const auto p = fullProgram();
  const auto bytes = writeBytecode(*p);
  const auto q = readBytecode(bytes.data(), bytes.size());
  BOOST_TEST(q->nodeSourceIds == p->nodeSourceIds);
  BOOST_TEST(q->strings == p->strings);
  BOOST_TEST(q->scheduling.defaultPriority == 1e-300);
  BOOST_TEST(q->scheduling.initialPriority == -1.5);
  BOOST_TEST((q->scheduling.order == PriorityOrder::Asc));
  BOOST_TEST(q->predicates[q->predicates.find("total")].aggregated());
  BOOST_TEST(q->predicates[q->predicates.find("edge")].route);
  BOOST_TEST(q->types.name(7) == ":(int, float)");
  BOOST_TEST(q->rules[2].block.code == p->rules[2].block.code);
  BOOST_TEST(q->highestArg == 1u);
}

BOOST_AUTO_TEST_CASE(file_io) {
  const auto p = fullProgram();
  const auto bytes = writeBytecode(*p);
  const auto path = std::filesystem::path(MELD_BINARY_DIR) / "tests/vm_test_bytecode.mbc";  // per build dir
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  BOOST_TEST((writeBytecode(*readBytecodeFile(path.string())) == bytes));
  std::filesystem::remove(path);
  BOOST_CHECK_EXCEPTION(readBytecodeFile(path.string()), BytecodeError,
                        [](const BytecodeError& e) { return contains(e.what(), "cannot open"); });
  BOOST_CHECK_EXCEPTION(readBytecodeFile(std::filesystem::temp_directory_path().string()), BytecodeError,
                        [](const BytecodeError& e) { return contains(e.what(), "cannot read"); });
}

BOOST_AUTO_TEST_CASE(every_truncation_is_rejected) {
  const auto bytes = writeBytecode(*fullProgram());
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::string why = readError({bytes.begin(), bytes.begin() + n});
    BOOST_TEST_REQUIRE(!why.empty(), "prefix of " << n << " bytes accepted");
    BOOST_TEST(contains(why, "truncated"), n << ": " << why);
  }
}

BOOST_AUTO_TEST_CASE(byte_flips_never_crash) {
  const auto bytes = writeBytecode(*fullProgram());
  std::size_t rejected = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i)
    for (std::uint8_t x : {0x01, 0x02, 0x10, 0x80, 0xff}) {
      auto changed = bytes;
      changed[i] ^= x;
      rejected += !readError(changed).empty();
    }
  BOOST_TEST_MESSAGE(rejected << " of " << 5 * bytes.size() << " byte flips rejected");
  BOOST_TEST(rejected > bytes.size());
}

BOOST_AUTO_TEST_CASE(random_word_changes_never_crash) {
  const auto bytes = writeBytecode(*fullProgram());
  std::mt19937 rng(20261121);
  const std::uint32_t interesting[] = {0, 1,  2,          3,          4,          5,
                                       6, 12, 0x7fffffff, 0x80000000, 0xfffffffe, 0xffffffff};
  for (int i = 0; i < 4000; ++i) {
    auto changed = bytes;
    const std::size_t at = (rng() % (bytes.size() / 4)) * 4;
    put(changed, at, i % 2 ? interesting[rng() % std::size(interesting)] : std::uint32_t(rng()));
    if (i % 3 == 0) changed[rng() % changed.size()] = std::uint8_t(rng());
    (void)readError(changed);
  }
}

BOOST_AUTO_TEST_CASE(header_errors) {
  const auto good = writeBytecode(*smallProgram());
  auto bytes = good;
  bytes[0] = 'X';
  BOOST_TEST(contains(readError(bytes), "magic"));

  bytes = good;
  put(bytes, 4, 5);
  const std::string version = readError(bytes);
  BOOST_TEST(contains(version, "version 5"), version);
  BOOST_TEST(contains(version, "this VM reads versions 1 to 4"), version);
  // Version 1 and 2 files, without the additions of the later versions, still load (the small
  // program has no AXIOM_FACTS, which came with version 4).
  for (std::uint32_t v : {1u, 2u}) {
    bytes = asVersion(writeBytecode(*smallProgram()), v);
    const auto p = readBytecode(bytes.data(), bytes.size());
    BOOST_TEST(p->sourceFiles.empty());
    BOOST_TEST(p->rules[1].block.lines.empty());
  }
  bytes = good;
  put(bytes, 4, 3);  // so do version 3 files
  BOOST_TEST(readBytecode(bytes.data(), bytes.size())->rules.size() == smallProgram()->rules.size());
  bytes = good;
  put(bytes, 8, 12);  // a version 3 or 4 file needs its sources section
  BOOST_TEST(contains(readError(bytes), "section count 12 (expected 13)"));

  bytes = good;
  put(bytes, 12, 99);  // the first section's tag
  BOOST_TEST(contains(readError(bytes), "unknown section tag 99"));

  bytes = good;
  put(bytes, 12, 2);
  BOOST_TEST(contains(readError(bytes), "out of order"));

  bytes = good;
  put(bytes, 20, 0x7ffffff0);  // the type count
  const std::string count = readError(bytes);
  BOOST_TEST(contains(count, "exceeds"), count);

  bytes = good;
  bytes.insert(bytes.end(), {0, 0, 0, 0});
  BOOST_TEST(contains(readError(bytes), "trailing garbage"));

  bytes = good;
  bytes.resize(30);
  const std::string truncated = readError(bytes);
  BOOST_TEST(contains(truncated, "truncated"), truncated);
  BOOST_TEST(contains(truncated, "at byte"), truncated);
}

// Verification errors of the file come out of readBytecode as well.
BOOST_AUTO_TEST_CASE(source_lines_round_trip_and_are_checked) {
  const auto p = fullProgram();
  auto bytes = writeBytecode(*p);
  const auto q = readBytecode(bytes.data(), bytes.size());
  BOOST_TEST(q->sourceFiles == p->sourceFiles);
  BOOST_TEST((q->axiomBlocks[0].lines == p->axiomBlocks[0].lines));
  BOOST_TEST((q->rules[1].block.lines == p->rules[1].block.lines));
  const SourceLine* l = q->axiomBlocks[0].lineAt(9);
  BOOST_REQUIRE(l);
  BOOST_TEST(l->line == 12u);
  BOOST_TEST(q->sourceFiles[l->file] == "lib/include.meld");
  BOOST_TEST(q->rules[0].block.lineAt(0) == nullptr);
  // Each fact of AXIOM_FACTS has the line in force at its first data word.
  for (const auto& [word, line] : {std::pair{22u, 13u}, {25u, 14u}, {31u, 15u}}) {
    BOOST_REQUIRE(q->axiomBlocks[0].lineAt(word));
    BOOST_TEST(q->axiomBlocks[0].lineAt(word)->line == line);
  }

  auto bad = fullProgram();
  bad->rules[1].block.lines = {{0, 2, 9}};  // no file 2
  bytes = writeBytecode(*bad);
  BOOST_TEST(contains(readError(bytes), "out of order or out of range"));
  bad = fullProgram();
  bad->axiomBlocks[0].lines = {{7, 0, 3}, {0, 0, 4}};  // pcs must increase
  bytes = writeBytecode(*bad);
  BOOST_TEST(contains(readError(bytes), "out of order or out of range"));
  bad = fullProgram();
  bad->rules[1].block.lines = {{100000, 0, 9}};  // past the code
  bytes = writeBytecode(*bad);
  BOOST_TEST(contains(readError(bytes), "out of order or out of range"));
}

// A block of literal facts only (AXIOM_FACTS and RET, no registers, no slots) comes back in
// Program::literalAxioms, numbered after the other axiom blocks, its lines and label kept; the
// verifier checks it as it checks the others.
namespace {

// fullProgram() with a block of literal facts (`literal`) as the file's axiom block 0; the general
// one is 1.
struct WithLiteralAxioms {
  std::unique_ptr<Program> program;
  CodeBlock literal;
};
WithLiteralAxioms withLiteralAxioms() {
  auto p = fullProgram();
  const PredId c = p->predicates.find("c"), edge = p->predicates.find("edge");
  CodeBlock literal;
  literal.label = "axioms of node 1";
  emit(literal, Opcode::AXIOM_FACTS, {edge, 2, 3, 0});
  emit(literal, Opcode::AXIOM_FACTS, {c, 3, 4, lo(0.25), hi(0.25)});
  emit(literal, Opcode::RET);
  literal.lines = {{3, 0, 20}, {4, 1, 21}, {5, 0, 22}};
  p->axiomBlocks.insert(p->axiomBlocks.begin(), literal);
  p->nodeAxioms = {1, 0, 1, Program::kNoAxioms};
  return {std::move(p), std::move(literal)};
}

}  // namespace

BOOST_AUTO_TEST_CASE(literal_axiom_blocks_are_read_back_to_back) {
  auto [p, literal] = withLiteralAxioms();
  const PredId edge = p->predicates.find("edge");
  const std::vector<std::uint32_t> code = literal.code;
  BOOST_REQUIRE_EQUAL(verifyError(*p), "");
  const auto bytes = writeBytecode(*p);
  const auto q = readBytecode(bytes.data(), bytes.size());
  BOOST_REQUIRE_EQUAL(q->axiomBlocks.size(), 1u);
  BOOST_REQUIRE_EQUAL(q->literalAxioms.size(), 1u);
  BOOST_TEST(q->axiomBlocks[0].registerTypes.size() == 3u);  // the general one
  BOOST_TEST((q->nodeAxioms == std::vector<std::uint32_t>{0, 1, 0, Program::kNoAxioms}));
  const auto got = q->literalAxioms.code(0);
  BOOST_TEST((std::vector<std::uint32_t>(got.begin(), got.end()) == code));
  BOOST_TEST(q->literalAxioms.label(0) == "axioms of node 1");
  const auto lines = q->literalAxioms.lines(0);
  BOOST_TEST((std::vector<SourceLine>(lines.begin(), lines.end()) == literal.lines));
  BOOST_TEST(lineAt(lines, 8)->line == 22u);  // c's fact: the line in force at its first data word
  BOOST_TEST((q->axiomCode(1).data() == got.data()));
  // Written back general first: read again, the same program and the same bytes. The writer puts
  // literal blocks after the others whatever the Program's order (meldc's Programs hold them among
  // the others), so p's own bytes are those too: one encoding per program, as the fuzz target checks.
  const auto again = writeBytecode(*q);
  BOOST_TEST((again == bytes));
  const auto r = readBytecode(again.data(), again.size());
  BOOST_TEST((writeBytecode(*r) == again));
  BOOST_TEST(listing(*r) == listing(*q));
  BOOST_TEST(listing(*q).find("axioms 1 of node 1") != std::string::npos);

  auto bad = [&](std::vector<std::uint32_t> words) {
    auto b = readBytecode(bytes.data(), bytes.size());
    b->literalAxioms = {};
    b->literalAxioms.add(words, "axioms of node 1");
    return verifyError(*b);
  };
  BOOST_TEST(bad(code) == "");
  std::string e = bad({std::uint32_t(Opcode::AXIOM_FACTS), edge, 1, 9, std::uint32_t(Opcode::RET)});
  BOOST_TEST(e == "axioms 1 (axioms of node 1): word 0: AXIOM_FACTS: node @9 at word 3 is not one of the "
                  "program's 4 nodes",
             e);
  e = bad({std::uint32_t(Opcode::AXIOM_FACTS), edge, 1, 2});
  BOOST_TEST(e == "axioms 1 (axioms of node 1): does not end with RET", e);
  e = bad({std::uint32_t(Opcode::AXIOM_FACTS), edge, 5, 2, std::uint32_t(Opcode::RET)});
  BOOST_TEST(contains(e, "axioms 1 (axioms of node 1): word 0: "), e);
  BOOST_TEST(contains(e, "runs past the end of the block"), e);
  e = bad({std::uint32_t(Opcode::RET), std::uint32_t(Opcode::RET)});
  BOOST_TEST(e == "axioms 1 (axioms of node 1): word 0: RET: a block of literal axioms holds AXIOM_FACTS and "
                  "a final RET only",
             e);
  e = bad({std::uint32_t(Opcode::AXIOM_FACTS), 99, 0, std::uint32_t(Opcode::RET)});
  BOOST_TEST(e == "axioms 1 (axioms of node 1): word 0: AXIOM_FACTS: unknown predicate 99", e);
  auto far = readBytecode(bytes.data(), bytes.size());
  far->nodeAxioms[3] = 2;
  BOOST_TEST(contains(verifyError(*far), "node 3: unknown axiom block 2"), verifyError(*far));
}

// Read in place (readBytecodeInPlace, readBytecodeFile), literal axiom blocks are not copied: their
// code, label and lines are those of the bytes, which the program keeps alive; the program is the
// one a copying read makes. Bytes that cannot be read as words where they lie are copied.
BOOST_AUTO_TEST_CASE(literal_axiom_blocks_are_read_in_place) {
  const WithLiteralAxioms made = withLiteralAxioms();
  const CodeBlock* literal = &made.literal;
  const auto bytes = writeBytecode(*made.program);
  const auto copied = readBytecode(bytes.data(), bytes.size());
  BOOST_TEST(!copied->literalAxioms.viewing());
  auto owner = std::make_shared<std::vector<std::uint8_t>>(bytes);
  const std::uint8_t* from = owner->data();
  const std::weak_ptr<std::vector<std::uint8_t>> watch = owner;
  auto viewed = readBytecodeInPlace(from, bytes.size(), std::move(owner));
  BOOST_REQUIRE(viewed->literalAxioms.viewing());
  BOOST_REQUIRE_EQUAL(viewed->literalAxioms.size(), 1u);
  const auto code = viewed->literalAxioms.code(0);
  const auto* at = reinterpret_cast<const std::uint8_t*>(code.data());
  BOOST_TEST((at > from && at + code.size_bytes() <= from + bytes.size()));  // in the bytes, not a copy
  BOOST_TEST((std::vector<std::uint32_t>(code.begin(), code.end()) == literal->code));
  BOOST_TEST(viewed->literalAxioms.label(0) == "axioms of node 1");
  const auto lines = viewed->literalAxioms.lines(0);
  BOOST_TEST((std::vector<SourceLine>(lines.begin(), lines.end()) == literal->lines));
  BOOST_TEST((writeBytecode(*viewed) == bytes));
  BOOST_TEST(listing(*viewed) == listing(*copied));
  BOOST_TEST(!watch.expired());  // kept by the program
  viewed.reset();
  BOOST_TEST(watch.expired());

  // Nothing to view (no literal axiom block): the bytes are not kept.
  auto plainOwner = std::make_shared<std::vector<std::uint8_t>>(writeBytecode(*fullProgram()));
  const std::weak_ptr<std::vector<std::uint8_t>> plainWatch = plainOwner;
  const std::uint8_t* plainBytes = plainOwner->data();
  const std::size_t plainSize = plainOwner->size();
  const auto plain = readBytecodeInPlace(plainBytes, plainSize, std::move(plainOwner));
  BOOST_TEST(!plain->literalAxioms.viewing());
  BOOST_TEST(plainWatch.expired());

  // Not on a word boundary: copied, the same program.
  std::vector<std::uint8_t> shifted(bytes.size() + 1);
  std::copy(bytes.begin(), bytes.end(), shifted.begin() + 1);
  const auto unaligned = readBytecodeInPlace(shifted.data() + 1, bytes.size(), nullptr);
  BOOST_TEST(!unaligned->literalAxioms.viewing());
  BOOST_TEST((writeBytecode(*unaligned) == bytes));

  // From a file: its mapping, kept by the program.
  const auto path = std::filesystem::path(MELD_BINARY_DIR) / "tests/vm_test_bytecode_in_place.mbc";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const auto mapped = readBytecodeFile(path.string());
  std::filesystem::remove(path);
  BOOST_TEST(mapped->literalAxioms.viewing());
  BOOST_TEST(listing(*mapped) == listing(*copied));

  // A bad source line of a literal block is refused either way, with the same message.
  auto badLines = withLiteralAxioms().program;
  badLines->axiomBlocks[0].lines = {{3, 0, 20}, {3, 0, 21}};  // not increasing
  const auto bad = writeBytecode(*badLines);
  const std::string copiedError = readError(bad);
  BOOST_TEST(contains(copiedError, "source line 1 of block 'axioms of node 1' is out of order"), copiedError);
  auto badOwner = std::make_shared<std::vector<std::uint8_t>>(bad);
  try {
    readBytecodeInPlace(badOwner->data(), badOwner->size(), badOwner);
    BOOST_ERROR("bad source lines read in place were accepted");
  } catch (const BytecodeError& e) {
    BOOST_TEST(std::string(e.what()) == copiedError);
  }
}

BOOST_AUTO_TEST_CASE(reader_verifies) {
  auto p = smallProgram();
  p->rules[1].block.registerTypes[3] = TypeTable::kFloat;
  const auto bytes = writeBytecode(*p);
  BOOST_TEST(contains(readError(bytes), "register 3 has type float, expected int"));
}

// Keeps vm/fuzz/corpus in step with the format: run with MELD_UPDATE_CORPUS=1 to rewrite it.
BOOST_AUTO_TEST_CASE(fuzz_corpus_is_current) {
  const std::filesystem::path dir = std::filesystem::path(MELD_SOURCE_DIR) / "vm/fuzz/corpus";
  const std::pair<const char*, std::unique_ptr<Program> (*)()> seeds[] = {{"small.mbc", smallProgram},
                                                                          {"full.mbc", fullProgram}};
  for (const auto& [name, make] : seeds) {
    const auto bytes = writeBytecode(*make());
    if (std::getenv("MELD_UPDATE_CORPUS"))
      std::ofstream(dir / name, std::ios::binary)
          .write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    std::ifstream in(dir / name, std::ios::binary);
    const std::vector<std::uint8_t> seed((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
    BOOST_TEST((seed == bytes), name << " is stale: rerun with MELD_UPDATE_CORPUS=1");
  }
}

BOOST_AUTO_TEST_CASE(disassembly_golden) {
  const std::string expected = R"(; Meld bytecode version 4

types:
  0  int
  1  float
  2  bool
  3  node
  4  thread
  5  string

predicates:
  0  _init() linear init
  1  a(node, int) linear
  2  b(node, int) linear

nodes:
  0 -> @0

scheduling: desc

globals
  registers: none
  slots: 0
  0000  RET

rule 0: _init -o axioms
  body: _init
  registers: none
  slots: 1
  0000  ITER      p=_init(0) s=0 flags=linear|consume j=0009
  0005  AXIOMS
  0006  FIRE      s=0
  0008  NEXT
  0009  RET

rule 1: a(A, N) -o b(A, N+1)
  body: a
  registers: r0 node, r1 int, r2 int, r3 int
  slots: 1
  0000  ITER      p=a(2) s=0 flags=linear|consume j=0028
  0005  LOAD      s=0 f=0 r0
  0009  LOAD      s=0 f=1 r1
  0013  MOVI      r2 1
  0016  ADDI      r3 r1 r2
  0020  DERIVE    p=b(2) (r0, r3)
  0025  FIRE      s=0
  0027  NEXT
  0028  RET
)";
  BOOST_TEST(listing(*smallProgram()) == expected);
}

BOOST_AUTO_TEST_CASE(disassembly_names_operands) {
  const std::string text = listing(*fullProgram());
  for (const char* part :
       {"p=c(2) s=0 flags=0 f=0 j=", "fn=inc (r0)", "b=llength t=<int> (r5)", "k=\"with \\\"quotes\\\"\\n\"",
        "g=limit", "MOVF      r2 0.1", "flags=move-to-back", "t=<:(int, float)> (r0, r1)",
        "process on c: !c(X, Y) -> total(X)", "axioms 0 of nodes 0 2", "3 -> @1099511627776",
        "scheduling: asc, initial -1.5, default 1e-300, static", "index: c(2) field 1",
        "7  total(int) persistent aggregate sum field 0", "MOVI      r2 -3",
        "AXIOM_FACTS p=c(2) 2 facts\n                 (-7, -0.5)\n                 (2, 1e+10)\n",
        "AXIOM_FACTS p=edge(1) 1 facts\n                 (@3)\n"})
    BOOST_TEST(contains(text, part), part);
}
