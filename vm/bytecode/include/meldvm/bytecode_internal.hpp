// Pieces shared by the bytecode writer, reader, verifier and disassembler; not part of the API.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "meldvm/program.hpp"

namespace meldvm::detail {

// Section tags of the `.mbc` layout, in file order (bytecode.hpp). Tag 0 is never used so that a
// zeroed word is never mistaken for a section.
enum SectionTag : std::uint32_t {
  kSecTypes = 1,
  kSecPredicates,
  kSecNodes,
  kSecStrings,
  kSecGlobals,
  kSecFunctions,
  kSecExterns,
  kSecRules,
  kSecProcesses,
  kSecAxioms,
  kSecScheduling,
  kSecIndexes,
  kSecSources,  // version 3 on
};
inline constexpr std::uint32_t kSectionCount = kSecSources;
// The sections a file of that version has.
inline constexpr std::uint32_t sectionCountOf(std::uint32_t version) {
  return version >= 3 ? kSecSources : kSecIndexes;
}
// The code blocks of a program before its axiom blocks, in the order of the sources section (the
// axiom blocks follow: Program::axiomBlocks, then the literalAxioms).
template <class P, class F>
void forEachCodeBlockBeforeAxioms(P& program, F&& f) {
  f(program.globalsInit);
  for (auto& fn : program.functions) f(fn.block);
  for (auto& r : program.rules) f(r.block);
  for (auto& pr : program.processes) f(pr.block);
}
inline std::size_t codeBlockCount(const Program& p) {
  return 1 + p.functions.size() + p.rules.size() + p.processes.size() + p.axiomBlockCount();
}
// Whether verified or unverified code is literal axioms (LiteralAxioms): AXIOM_FACTS
// instructions and a RET that ends it. (A block of them also has no registers and no slots.)
bool literalAxiomCode(std::span<const std::uint32_t> code);
// The length of the AXIOM_FACTS at `pos` when it is one and its data words are all in `code`,
// else 0: a data file's thousands of them, without instructionLength's general decoding.
inline std::size_t axiomFactsLength(std::span<const std::uint32_t> code, std::size_t pos) {
  const std::size_t left = code.size() - pos;
  if (Opcode(code[pos]) != Opcode::AXIOM_FACTS || left < 3 || code[pos + 2] > left - 3) return 0;
  return 3 + std::size_t(code[pos + 2]);
}
const char* sectionName(std::uint32_t tag);  // "?" for unknown tags

inline constexpr char kMagic[4] = {'M', 'B', 'C', '1'};

// PredicateDesc booleans as one word.
inline constexpr std::uint32_t kPredLinear = 1, kPredRoute = 2, kPredReverseRoute = 4, kPredAction = 8,
                               kPredThread = 16, kPredCompact = 32;
inline constexpr std::uint32_t kPredFlagsAll = 63;

// SchedulingOptions booleans as one word.
inline constexpr std::uint32_t kSchedInitial = 1, kSchedDefault = 2, kSchedNoInitial = 4, kSchedStatic = 8;
// With kSchedNoPriority a third double (the no-priority value) follows the two of version 1 files.
inline constexpr std::uint32_t kSchedNoPriority = 16;
inline constexpr std::uint32_t kSchedFlagsAll = 31;

// Length in words of the instruction at `pos` of `code`, or 0 when it is malformed (unknown opcode,
// operands running past the end); then `why` says what is wrong.
std::size_t instructionLength(std::span<const std::uint32_t> code, std::size_t pos, std::string& why);

// AXIOM_FACTS: the data words of one fact of a predicate with these fields (one per int, bool or
// node field, two per float field), or 0 when a field has another type or there is none (such
// facts are derived with DERIVE).
inline std::size_t axiomFactWords(std::span<const TypeId> fields) {
  std::size_t n = 0;
  for (const TypeId t : fields) {
    if (t == TypeTable::kFloat)
      n += 2;
    else if (t == TypeTable::kInt || t == TypeTable::kBool || t == TypeTable::kNode)
      n += 1;
    else
      return 0;
  }
  return n;
}
// The field of type t (one axiomFactWords accepts) whose data words start at w; `w` moves past them.
inline Value axiomField(TypeId t, const std::uint32_t*& w) {
  switch (t) {
    case TypeTable::kFloat: {
      const std::uint64_t bits = std::uint64_t(w[0]) | std::uint64_t(w[1]) << 32;
      w += 2;
      return Value::fromFloat(std::bit_cast<double>(bits));
    }
    case TypeTable::kInt:
      return Value::fromInt(std::int32_t(*w++));
    case TypeTable::kBool:
      return Value::fromBool(*w++ != 0);
    default:
      return Value::fromNode(*w++);
  }
}

// Calls f(pos) for every instruction of verified code, in order (for the run-time summaries the
// Machine and the interpreter draw from a block once).
template <class F>
void forEachInstruction(std::span<const std::uint32_t> code, F&& f) {
  std::string why;
  for (std::size_t pos = 0; pos < code.size();) {
    const std::size_t len = instructionLength(code, pos, why);
    if (len == 0) return;  // the verifier accepted the block: cannot happen
    f(pos);
    pos += len;
  }
}

// The facts an axiom block (verified) stores: f(predicate, count) for each DERIVE (one fact) and
// AXIOM_FACTS (its data words hold whole facts of axiomFactWords each).
// (AXIOM_FACTS, most of a data file's axiom blocks, is stepped over by axiomFactsLength: through
// instructionLength, the count before the start took pagerank-movies 1.8 M instructions.)
template <class F>
void forEachAxiomStore(const Program& program, std::span<const std::uint32_t> code, F&& f) {
  std::string why;
  for (std::size_t pc = 0; pc < code.size();) {
    if (const std::size_t len = axiomFactsLength(code, pc)) {
      const PredId p = code[pc + 1];
      if (const std::size_t per = axiomFactWords(program.predicates[p].fields))
        f(p, std::size_t(code[pc + 2]) / per);
      pc += len;
      continue;
    }
    if (Opcode(code[pc]) == Opcode::DERIVE) f(PredId(code[pc + 1]), std::size_t(1));
    const std::size_t len = instructionLength(code, pc, why);
    if (len == 0) return;  // the verifier accepted the block: cannot happen
    pc += len;
  }
}

// ITER, ITER_KEY and ITER_SORTED: operands predicate, slot, flags (IterFlags), then their own.
inline bool isLoop(std::uint32_t opcode) {
  const auto op = Opcode(opcode);
  return op == Opcode::ITER || op == Opcode::ITER_KEY || op == Opcode::ITER_SORTED;
}

// The first field of predicate p that holds a list, or -1.
std::int32_t firstListField(const Program& program, PredId p);
// How many facts ahead a loop over lists fetches them (listFetchDepth): the first cell of the list
// five facts on, the second cell four facts on, and so on to the fifth cell one fact on, each one
// visit after the cell that leads to it. n-queens 13 walks lists of up to 12 cells: 3 facts ahead
// ran it in 3.52 s, 5 in 2.99 s, 9 in 2.66 s (2-core VM, 2026-11-28, medians of 5 runs, user CPU s);
// 8queens-12 (lists of up to 11) ran as fast with 5 as with 3, 9 cost it 11 % (the walk to the deepest cells
// is repeated at every visit).
inline constexpr int kListFetchAhead = 5;
// For the loop instruction at loopPc of verified code, how deep it fetches the lists of the facts
// it visits next, or -1 for not at all. Walking a list waits for memory at every cell (the cells
// of one list were consed at different times and lie apart). Only an ITER over a linear predicate
// with a list field whose body (up to the loop's end) loads that field fetches: kListFetchAhead - 1
// (the whole pipeline) when a loaded register goes to a built-in or user function, which may walk
// the list; 0 (only the first cell of the fact kListFetchAhead on, which the load's reference count
// touches) when the list is only moved on. The interpreter and native code fetch alike.
int listFetchDepth(const Program& program, std::span<const std::uint32_t> code, std::size_t loopPc);
// The (predicate, argument) pairs a program looks up by key: its `index p/N` directives (the valid
// ones) and its ITER_KEY loops. The VM indexes each (ProgramTables::keyLookups); native code knows
// from them which linear predicates may have indexed tables.
std::vector<std::pair<PredId, std::uint32_t>> keyLookups(const Program& program);
// A loop body (from `body`) that begins by loading arguments of the fact in `slot` and looks one of
// them up as the key of an ITER_KEY (pagerank's neighbour, new-heat-transfer's): that argument,
// and the ITER_KEY's predicate and argument. Its look-ups of consecutive facts land anywhere in
// the index's hash table, so native code fetches the entry of the next fact's key while it visits
// a fact (a third of new-heat-transfer's cache misses were those entries). (The interpreter did
// the same in its open loops and lost: new-heat-transfer-80 720 -> 751 ms, pagerank unchanged.)
struct KeyJoin {
  std::uint32_t field;   // of the loop's fact
  PredId pred;           // the ITER_KEY's
  std::uint32_t keyArg;  // the ITER_KEY's argument
};
std::optional<KeyJoin> keyJoinAt(std::span<const std::uint32_t> code, std::size_t body, std::uint32_t slot);
// How many facts ahead a loop whose lists stay put fetches them (listsStayPut): each visit reads
// one cell per fact ahead, not the walks above, so it goes further. n-queens 13 bytecode 5.89 s
// with 5 walked afresh, 5.92 s with 5 carried, 5.35 s with 9 carried; 8queens-12 5.47 s, 5.13 s,
// 5.23 s (2-core VM in a slow window, 2026-11-28, medians of 9 and 7 interleaved runs).
inline constexpr int kListPipelineAhead = 9;
// A carried list goes one cell deeper every kListPipelineSpacing visits, so the facts whose cells
// are on the way are that many times kListPipelineAhead, and each cell fetched has that many
// visits to arrive before the step that reads its tail. One visit was too short on this VM: the
// steps waited for the cells the step before fetched, a quarter of 8queens-12's samples. With 2:
// 8queens-12 bytecode 2.190 -> 2.039 s, n-queens 13 2.270 -> 2.152 s (2-core AMD EPYC VM,
// 2026-11-29, medians of 7 interleaved runs; 1.7 % more instructions, the shifts of a longer
// array). 3 lost the gain to those shifts.
inline constexpr int kListPipelineSpacing = 2;
inline constexpr int kListPipelineFacts = kListPipelineAhead * kListPipelineSpacing;
// The depth of the cell on the way for the fact k on (1 <= k <= kListPipelineFacts).
constexpr int listPipelineDepth(int k) { return (kListPipelineFacts - k) / kListPipelineSpacing; }
// Whether the lists of the facts a loop of this block visits stay put while it runs: no UPDATE in
// the block gives a fact new arguments (and may free its old list). Then the loop may carry the
// cells it fetched from one visit to the next, one cell deeper each time (ListPipeline), instead
// of walking every list again from its first cell.
bool listsStayPut(std::span<const std::uint32_t> code);
// The register the instruction at `pos` of verified code computes (writtenRegisterOperand), or -1.
std::int64_t writtenRegister(std::span<const std::uint32_t> code, std::size_t pos);
// The outermost loop around the instruction at `pos` of verified code whose body (to its end)
// never writes register r, as the position of its loop instruction; -1 when there is none. While
// one run of that loop lasts, r holds one value: what an instruction at `pos` computes from r
// alone may be computed once per run of the loop (native code's queens_violation).
std::int64_t outermostLoopKeeping(std::span<const std::uint32_t> code, std::size_t pos, std::uint32_t r);

// TypeTable::name with the nesting depth capped: a file can chain thousands of `list` types, and
// the unbounded recursion of TypeTable::name would then overflow the stack.
std::string typeName(const TypeTable& types, TypeId t);

}  // namespace meldvm::detail
