// A compiled Meld program as the VM runs it: the tables and code blocks that meldc lowers a program
// to and that a `.mbc` file stores (bytecode.hpp reads and writes it). Instructions are the
// opcodes of opcodes.def.
//
// Rules (§6.4.1): `rules[0]` is the node initialisation rule (`_init -o axioms`), then the
// numbered (non-persistent) user rules in priority order. Persistent rules (§6.5) are not numbered:
// they become `processes`, one code block per (persistent rule, occurrence of a predicate in its
// body), run when a fact of that predicate first appears at a node with slot 0 bound to it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "meldvm/literal_axioms.hpp"
#include "meldvm/predicate.hpp"
#include "meldvm/source_line.hpp"
#include "meldvm/types.hpp"
#include "meldvm/value.hpp"

namespace meldvm {

enum class Opcode : std::uint32_t {
#define OP(name, operands, meaning) name,
#include "meldvm/opcodes.def"
#undef OP
  Count
};

struct OpcodeInfo {
  const char* name;
  const char* operands;  // letters as documented in opcodes.def
  const char* meaning;
};
// The table of opcodes.def, indexed by opcode.
const OpcodeInfo& opcodeInfo(Opcode op);
// The operand (position in the letters) of the register the instruction computes, -1 if none;
// derived from the meaning column of opcodes.def ("r0 = ...").
int writtenRegisterOperand(Opcode op);
inline constexpr std::uint32_t kOpcodeCount = std::uint32_t(Opcode::Count);

// Flag bits of ITER / ITER_KEY / ITER_SORTED (operand X).
enum IterFlags : std::uint32_t {
  kIterLinear = 1,        // the predicate is linear: skip consumed facts and facts bound by enclosing loops
  kIterConsume = 2,       // FIRE/CFIRE consume the fact bound here
  kIterReturnOnFire = 4,  // §6.4.3: an enclosing loop iterates a consumable linear subgoal
  kIterRandom = 8,        // ITER_SORTED: random order ([:random] selector) instead of ascending
  kIterConsumableClass = 16,  // counts as "iterates a consumable linear subgoal" for nested loops
  kIterThread = 32,           // iterate the facts of the running thread's node (§6.12), not the host's
};
// Flag bits of UPDATE.
enum UpdateFlags : std::uint32_t { kUpdateMoveToBack = 1 };

// A sequence of instructions with its register file and fact slots.
struct CodeBlock {
  std::vector<std::uint32_t> code;
  std::vector<TypeId> registerTypes;  // one per register
  std::uint32_t slots = 0;            // fact slots used by loops
  std::string label;                  // for messages and the disassembly, e.g. the rule's source text
  std::vector<SourceLine> lines;      // by increasing pc; empty when unknown (bytecode before v3)

  // The source line of the instruction at `pc`, or nullptr.
  const SourceLine* lineAt(std::uint32_t pc) const { return meldvm::lineAt(lines, pc); }
};

struct Rule {
  CodeBlock block;
  // Distinct predicates of the body (the candidate test of §6.4.2): the rule is a candidate when
  // each has at least one fact at the node.
  std::vector<PredId> bodyPredicates;
};

struct Process {
  PredId trigger;  // slot 0 of the block is bound to the new (or retracted) fact of this predicate
  CodeBlock block;
};

struct Global {  // a `const` computed at start-up (folded ones never reach the VM)
  std::string name;
  TypeId type;
};

struct Function {  // `fun name(params) : result = body.`
  std::string name;
  std::vector<TypeId> params;
  TypeId result;
  // Parameters arrive in registers 0..params.size()-1; the body leaves the result in register
  // params.size() and ends with RET.
  CodeBlock block;
};

struct Extern {
  std::string name;
  std::vector<TypeId> params;
  TypeId result;
};

enum class PriorityOrder : std::uint8_t { Desc, Asc };  // §6.11: @desc (default) serves larger first

struct SchedulingOptions {
  PriorityOrder order = PriorityOrder::Desc;
  bool hasInitialPriority = false;  // `priority @initial P.`
  double initialPriority = 0.0;
  bool hasDefaultPriority = false;  // `priority @default P.`
  double defaultPriority = 0.0;
  bool noInitialPriorities = false;  // `priority @no_initial_priorities.`
  bool hasNoPriority = false;        // `priority @no_priority P.`: P means "no priority"
  double noPriority = 0.0;
  bool staticNodes = false;  // `priority @static.`
};

struct IndexRequest {
  PredId predicate;
  std::uint32_t field;  // home excluded
};

// Not movable: the predicate table refers to the type table. Held by unique_ptr.
struct Program {
  Program() = default;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  TypeTable types;
  PredicateTable predicates{types};
  // Special predicates, looked up by the runtime (kNoPred when the program has none).
  static constexpr PredId kNoPred = 0xFFFFFFFFu;
  PredId initPredicate = kNoPred;  // `_init`

  // Initial nodes: internal id -> id in the source (§6.1).
  std::vector<std::int64_t> nodeSourceIds;
  std::vector<std::string> strings;      // string constants (MOVS)
  std::vector<std::string> sourceFiles;  // the files SourceLine::file indexes (as meldc named them)
  std::vector<Global> globals;
  CodeBlock globalsInit;  // computes the globals (SETGLOBAL), run once before any node runs
  std::vector<Function> functions;
  std::vector<Extern> externs;

  std::vector<Rule> rules;         // rules[0] = `_init -o axioms`
  std::vector<Process> processes;  // persistent rules, in program order
  // Constant axioms per initial node (run by AXIOMS in rule 0): the number of an axiom block, or
  // kNoAxioms. Blocks are numbered axiomBlocks first, then literalAxioms (as a file stores them;
  // the reader keeps the blocks of literal facts only in literalAxioms).
  static constexpr std::uint32_t kNoAxioms = 0xFFFFFFFFu;
  std::vector<std::uint32_t> nodeAxioms;  // one per initial node
  std::vector<CodeBlock> axiomBlocks;
  LiteralAxioms literalAxioms;
  std::size_t axiomBlockCount() const { return axiomBlocks.size() + literalAxioms.size(); }
  // The code of axiom block b (b < axiomBlockCount()).
  std::span<const std::uint32_t> axiomCode(std::uint32_t b) const {
    return b < axiomBlocks.size() ? std::span<const std::uint32_t>(axiomBlocks[b].code)
                                  : literalAxioms.code(b - axiomBlocks.size());
  }

  SchedulingOptions scheduling;
  std::vector<IndexRequest> indexes;
  std::uint32_t highestArg = 0;  // largest K of @argK used
};

// The code blocks that native code covers, in the order that numbers them (native block k is the
// k-th): the rules, the persistent processes, the functions, then the globals initialiser. Axiom
// blocks are not among them: each runs once, in the interpreter.
std::vector<const CodeBlock*> nativeCodeBlocks(const Program& program);

}  // namespace meldvm
