// verifyProgram: everything the interpreter relies on without checking at run time. The tables must
// refer to existing entries, and every code block must decode, use registers of the types its
// instructions expect, jump only to instruction boundaries of its own loop, and nest its loops.
#include <algorithm>
#include <functional>
#include <optional>
#include <type_traits>

#include "meldvm/builtin_signatures.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldvm {

namespace {

using detail::typeName;

enum class BlockKind { Globals, Function, Rule, Process, Axioms };

[[noreturn]] void fail(const std::string& what) { throw BytecodeError(what, 0); }

std::string n2s(std::uint64_t n) { return std::to_string(n); }

std::string titled(std::string head, const std::string& label) {
  return label.empty() ? head : head + " (" + label + ")";
}

// The data words of the AXIOM_FACTS at `at` (decoded: its predicate exists, its words are in the
// block): whole facts of a predicate whose fields all fit in them, with valid bools and nodes (the
// interpreter decodes them without a check). What is wrong, or nothing.
std::string axiomFactsProblem(const Program& p, std::span<const std::uint32_t> code, std::size_t at) {
  const PredId pred = code[at + 1];
  const std::uint32_t count = code[at + 2];
  const PredicateDesc& d = p.predicates[pred];
  const auto text = [&] { return d.name + "/" + n2s(d.arity()); };
  if (d.thread || d.action) return text() + " is a thread or action predicate";
  const std::size_t per = detail::axiomFactWords(d.fields);
  if (per == 0) return text() + " has a field that is not an int, float, bool or node";
  if (count % per != 0) return n2s(count) + " data words for facts of " + n2s(per) + " words each";
  const std::uint32_t nodes = std::uint32_t(std::min<std::size_t>(p.nodeSourceIds.size(), 0xFFFFFFFFu));
  const std::size_t arity = d.fields.size();
  for (std::size_t w = at + 3, end = at + 3 + count; w < end;)
    for (std::size_t i = 0; i < arity; ++i) {
      const TypeId t = d.fields[i];
      const std::uint32_t v = code[w];
      if (t == TypeTable::kFloat) {
        w += 2;
        continue;
      }
      if (t == TypeTable::kBool && v > 1) [[unlikely]]
        return "bool " + n2s(v) + " at word " + n2s(w) + " is not 0 or 1";
      if (t == TypeTable::kNode && v >= nodes) [[unlikely]]
        return "node @" + n2s(v) + " at word " + n2s(w) + " is not one of the program's " +
               n2s(p.nodeSourceIds.size()) + " nodes";
      ++w;
    }
  return {};
}

// A block of LiteralAxioms in one walk: a data file makes one per node, and BlockVerifier's passes
// cost more than checking the facts. Messages as BlockVerifier's.
void verifyLiteralAxioms(const Program& p, std::size_t i) {
  const std::span<const std::uint32_t> code = p.literalAxioms.code(i);
  const auto title = [&] {
    return titled("axioms " + n2s(p.axiomBlocks.size() + i), std::string(p.literalAxioms.label(i)));
  };
  if (code.empty()) fail(title() + ": empty code (no RET)");
  std::string why;
  for (std::size_t pos = 0; pos < code.size();) {
    const auto op = Opcode(code[pos]);
    // instructionLength only for what is not a whole AXIOM_FACTS (and its messages).
    std::size_t len = detail::axiomFactsLength(code, pos);
    if (len == 0) len = detail::instructionLength(code, pos, why);
    const auto bad = [&](const std::string& what) {
      fail(title() + ": word " + n2s(pos) + ": " + (len ? std::string(opcodeInfo(op).name) + ": " : "") +
           what);
    };
    if (len == 0) bad(why);
    if (op == Opcode::RET && pos + len == code.size()) return;
    if (op != Opcode::AXIOM_FACTS) bad("a block of literal axioms holds AXIOM_FACTS and a final RET only");
    if (code[pos + 1] >= p.predicates.size()) bad("unknown predicate " + n2s(code[pos + 1]));
    if (why = axiomFactsProblem(p, code, pos); !why.empty()) bad(why);
    pos += len;
  }
  fail(title() + ": does not end with RET");
}

struct Loop {
  std::size_t at;      // word offset of the ITER
  std::size_t exit;    // its J operand
  std::uint32_t slot;  // S operand
  PredId pred;
};
struct Jump {
  std::size_t from, target;
};

// The per-block working arrays, kept from one block to the next: a program may have hundreds of
// thousands of blocks (one per node's axioms), and allocating them per block was a third of the
// verifier's time.
struct VerifierScratch {
  std::vector<Loop> loops;            // open loops, innermost last
  std::vector<PredId> slotPred;       // per slot: the predicate of the open loop binding it, or kNoPred
  std::vector<bool> start;            // instruction boundaries
  std::vector<std::uint32_t> starts;  // the same, in order (passes 2 and 3 walk them)
  std::vector<std::size_t> region;    // per instruction start: the loop (ITER offset) it belongs to
  std::vector<Jump> jumps;
};

class BlockVerifier {
 public:
  // `title` names the block in messages; it is called only when one is needed.
  BlockVerifier(const Program& p, const CodeBlock& b, BlockKind kind, std::function<std::string()> title,
                VerifierScratch& scratch)
      : p_(p),
        b_(b),
        code_(b.code),
        kind_(kind),
        title_(std::move(title)),
        loops_(scratch.loops),
        slotPred_(scratch.slotPred),
        start_(scratch.start),
        starts_(scratch.starts),
        region_(scratch.region),
        jumps_(scratch.jumps) {
    loops_.clear();
    jumps_.clear();
  }

  const Function* function = nullptr;
  const Process* process = nullptr;
  bool isRule0 = false;

  void run();

 private:
  static constexpr std::size_t kTop = SIZE_MAX;  // region of code outside every loop

  [[noreturn]] void blockFail(const std::string& why) const { fail(title_() + ": " + why); }
  [[noreturn]] void bad(const std::string& why) const {
    fail(title_() + ": word " + n2s(at_) + ": " + opcodeInfo(Opcode(code_[at_])).name + ": " + why);
  }

  std::string regText(std::uint32_t r) const { return "register " + n2s(r); }
  TypeId reg(std::uint32_t r, char letter) const;
  // What a check is about: text, or a function making it, called only when the check fails (the
  // loader checks millions of operands: building every description up front cost more than the
  // checks themselves).
  template <class What>
  static std::string describe(const What& what) {
    if constexpr (std::is_invocable_v<const What&>)
      return what();
    else
      return std::string(what);
  }
  template <class What>
  void sameType(std::uint32_t r, TypeId want, const What& what) const {
    if (b_.registerTypes[r] != want) [[unlikely]]
      bad(regText(r) + " has type " + typeName(p_.types, b_.registerTypes[r]) + ", expected " +
          typeName(p_.types, want) + " (" + describe(what) + ")");
  }
  std::string predText(PredId pred) const {
    return p_.predicates[pred].name + "/" + n2s(p_.predicates[pred].arity());
  }
  // The predicate of the fact bound to slot S here, if any.
  std::optional<PredId> bound(std::uint32_t slot) const {
    if (slotPred_[slot] != Program::kNoPred) return slotPred_[slot];
    if (kind_ == BlockKind::Process && slot == 0) return process->trigger;
    return std::nullopt;
  }
  PredId needBound(std::uint32_t slot) const {
    const auto pred = bound(slot);
    if (!pred) bad("slot " + n2s(slot) + " is not bound here (no enclosing loop binds it)");
    return *pred;
  }
  void fieldInRange(PredId pred, std::uint32_t field) const {
    if (field >= p_.predicates[pred].arity())
      bad("field " + n2s(field) + " out of range for " + predText(pred));
  }
  // The registers of a '*' operand against a list of expected types.
  template <class What>
  void args(std::span<const TypeId> want, const What& what) const {
    if (count_ != want.size())
      bad(n2s(count_) + " registers for " + describe(what) + " of " + n2s(want.size()) + " arguments");
    for (std::size_t i = 0; i < want.size(); ++i)
      sameType(code_[list_ + i], want[i], [&] { return "argument " + n2s(i) + " of " + describe(what); });
  }

  void operands();
  void semantics();
  void axiomFacts();
  void definiteAssignment();

  const Program& p_;
  const CodeBlock& b_;
  std::span<const std::uint32_t> code_;
  BlockKind kind_;
  std::function<std::string()> title_;

  std::size_t at_ = 0;        // offset of the instruction being checked
  std::uint32_t v_[8] = {};   // its operand values by position in the letters ('*': the count)
  std::size_t list_ = 0;      // offset of the first register of the '*' operand
  std::uint32_t count_ = 0;   // and their number
  std::vector<Loop>& loops_;  // VerifierScratch's
  std::vector<PredId>& slotPred_;
  std::vector<bool>& start_;
  std::vector<std::uint32_t>& starts_;
  std::vector<std::size_t>& region_;
  std::vector<Jump>& jumps_;
};

TypeId BlockVerifier::reg(std::uint32_t r, char letter) const {
  if (r >= b_.registerTypes.size())
    bad(regText(r) + " out of range (the block has " + n2s(b_.registerTypes.size()) + " registers)");
  const TypeId t = b_.registerTypes[r];
  const TypeTable& types = p_.types;
  const char* want = nullptr;
  switch (letter) {
    case 'i':
      want = t == TypeTable::kInt ? nullptr : "int";
      break;
    case 'f':
      want = t == TypeTable::kFloat ? nullptr : "float";
      break;
    case 'b':
      want = t == TypeTable::kBool ? nullptr : "bool";
      break;
    case 'n':
      want = t == TypeTable::kNode ? nullptr : "node";
      break;
    case 'l':
      want = types.kind(t) == TypeKind::List ? nullptr : "a list";
      break;
    case 's':
      want = types.kind(t) == TypeKind::Struct ? nullptr : "a struct";
      break;
    default:
      break;
  }
  if (want) bad(regText(r) + " has type " + typeName(types, t) + ", expected " + want);
  return t;
}

// Letter by letter: ranges and register kinds. Opcode-specific rules follow in semantics().
void BlockVerifier::operands() {
  const std::string_view letters = opcodeInfo(Opcode(code_[at_])).operands;
  std::size_t w = at_ + 1;
  for (std::size_t k = 0; k < letters.size(); ++k) {
    const char letter = letters[k];
    const std::uint32_t v = code_[w];
    v_[k] = v;
    switch (letter) {
      case 'r':
      case 'i':
      case 'f':
      case 'b':
      case 'n':
      case 'l':
      case 's':
        reg(v, letter);
        break;
      case 'S':
        if (v >= b_.slots)
          bad("slot " + n2s(v) + " out of range (the block has " + n2s(b_.slots) + " slots)");
        break;
      case 'P':
        if (v >= p_.predicates.size()) bad("unknown predicate " + n2s(v));
        break;
      case 'T':
        if (v >= p_.types.size()) bad("unknown type " + n2s(v));
        break;
      case 'K':
        if (v >= p_.strings.size()) bad("unknown string constant " + n2s(v));
        break;
      case 'G':
        if (v >= p_.globals.size()) bad("unknown global " + n2s(v));
        break;
      case 'U':
        if (v >= p_.functions.size()) bad("unknown function " + n2s(v));
        break;
      case 'E':
        if (v >= p_.externs.size()) bad("unknown extern " + n2s(v));
        break;
      case 'B':
        // Ids the table lacks are built-ins the VM does not implement: refused before the run.
        if (v >= kBuiltinIdCount || !findBuiltin(std::uint16_t(v))) bad("unknown built-in " + n2s(v));
        break;
      case 'J':
        if (v >= code_.size())
          bad("jump target " + n2s(v) + " is outside the block (" + n2s(code_.size()) + " words)");
        if (!start_[v]) bad("jump target " + n2s(v) + " is not an instruction boundary");
        // Forward only: a block then ends after a bounded number of steps (loops go over facts).
        if (v <= at_) bad("jump target " + n2s(v) + " is not after the instruction");
        jumps_.push_back({at_, v});
        break;
      case '*':
        list_ = w + 1;
        count_ = v;
        for (std::uint32_t i = 0; i < v; ++i) reg(code_[list_ + i], 'r');
        break;
      case 'W':  // data words: checked by opcode
        list_ = w + 1;
        count_ = v;
        break;
      default:  // I, F, X: checked by opcode; D: any bits
        break;
    }
    w += letter == 'D' ? 2 : 1;
  }
}

void BlockVerifier::semantics() {
  const auto op = Opcode(code_[at_]);
  const auto& rt = b_.registerTypes;
  const TypeTable& types = p_.types;
  switch (op) {
    case Opcode::ITER:
    case Opcode::ITER_KEY:
    case Opcode::ITER_SORTED: {
      const PredId pred = v_[0];
      const std::uint32_t slot = v_[1], flags = v_[2];
      if (flags & ~std::uint32_t(63)) bad("unknown flag bits " + n2s(flags));
      // The flags must say what the predicate is: the interpreter trusts them (a linear loop over
      // persistent facts would consume them, a thread loop needs the thread node).
      const PredicateDesc& d = p_.predicates[pred];
      if (d.action) bad("a loop over the action " + predText(pred) + ": actions are run, never stored");
      if (bool(flags & kIterLinear) != d.linear)
        bad(std::string(d.linear ? "a loop over the linear " : "a linear loop over the persistent ") +
            predText(pred) + (d.linear ? " lacks the linear flag" : ""));
      if ((flags & kIterConsume) && !d.linear) bad("consumes facts of the persistent " + predText(pred));
      if (bool(flags & kIterThread) != d.thread)
        bad(std::string(d.thread ? "a loop over the thread predicate "
                                 : "a thread loop over the node predicate ") +
            predText(pred) + (d.thread ? " lacks the thread flag" : ""));
      if ((flags & kIterRandom) && op != Opcode::ITER_SORTED) bad("the random flag outside ITER_SORTED");
      if (bound(slot)) bad("slot " + n2s(slot) + " is already bound by an enclosing loop");
      if (op != Opcode::ITER) fieldInRange(pred, v_[3]);
      if (op == Opcode::ITER_KEY)
        sameType(v_[4], p_.predicates[pred].fields[v_[3]],
                 [&] { return "field " + n2s(v_[3]) + " of " + predText(pred); });
      const std::size_t exit = v_[op == Opcode::ITER ? 3 : op == Opcode::ITER_KEY ? 5 : 4];
      if (exit <= at_) bad("loop exit " + n2s(exit) + " is not after the loop");
      loops_.push_back({at_, exit, slot, pred});
      slotPred_[slot] = pred;
      break;
    }
    case Opcode::NEXT: {
      if (loops_.empty()) bad("NEXT outside a loop");
      const Loop& l = loops_.back();
      if (l.exit != at_ + 1)
        bad("closes the loop of word " + n2s(l.at) + " whose exit is word " + n2s(l.exit) +
            " (loops must nest)");
      slotPred_[l.slot] = Program::kNoPred;
      loops_.pop_back();
      break;
    }
    case Opcode::FIRE:
    case Opcode::CFIRE:
      if (loops_.empty()) bad("outside a loop");
      break;
    case Opcode::LOAD:
    case Opcode::TEST: {
      const PredId pred = needBound(v_[0]);
      fieldInRange(pred, v_[1]);
      sameType(v_[2], p_.predicates[pred].fields[v_[1]],
               [&] { return "field " + n2s(v_[1]) + " of " + predText(pred); });
      break;
    }
    case Opcode::MOV:
      sameType(v_[1], rt[v_[0]], "the destination's type");
      break;
    case Opcode::MOVB:
      if (v_[1] > 1) bad("bool immediate " + n2s(v_[1]) + " is not 0 or 1");
      break;
    case Opcode::MOVN:
      // Node literals name initial nodes (created ones exist only as values made at run time).
      if (v_[1] >= p_.nodeSourceIds.size())
        bad("node @" + n2s(v_[1]) + " is not one of the program's " + n2s(p_.nodeSourceIds.size()) +
            " nodes");
      break;
    case Opcode::MOVS:
      sameType(v_[0], TypeTable::kString, "a string constant");
      break;
    case Opcode::GLOBAL:
      sameType(v_[0], p_.globals[v_[1]].type, [&] { return "global " + p_.globals[v_[1]].name; });
      break;
    case Opcode::SETGLOBAL:
      if (kind_ != BlockKind::Globals) bad("outside the globals initialiser");
      sameType(v_[1], p_.globals[v_[0]].type, [&] { return "global " + p_.globals[v_[0]].name; });
      break;
    case Opcode::THREAD:
      sameType(v_[0], TypeTable::kThread, "@thread");
      break;
    case Opcode::ARG:
      sameType(v_[0], TypeTable::kString, "@arg");
      if (v_[1] < 1 || v_[1] > p_.highestArg)
        bad("argument " + n2s(v_[1]) + " outside 1.." + n2s(p_.highestArg) + " (the program's highest @arg)");
      break;
    case Opcode::EQ:
    case Opcode::NE:
      sameType(v_[1], v_[3], "the compared type");
      sameType(v_[2], v_[3], "the compared type");
      break;
    case Opcode::CONS:
      if (types.kind(v_[3]) != TypeKind::List) bad("type " + typeName(types, v_[3]) + " is not a list type");
      sameType(v_[0], v_[3], "the list type");
      sameType(v_[2], v_[3], "the list type");
      sameType(v_[1], types.element(v_[3]), "the element type");
      break;
    case Opcode::HEAD:
      sameType(v_[0], types.element(rt[v_[1]]), "the element type");
      break;
    case Opcode::TAIL:
      sameType(v_[0], rt[v_[1]], "the list type");
      break;
    case Opcode::STRUCT:
      if (types.kind(v_[1]) != TypeKind::Struct)
        bad("type " + typeName(types, v_[1]) + " is not a struct type");
      sameType(v_[0], v_[1], "the struct type");
      args(types.fields(v_[1]), [&] { return typeName(types, v_[1]); });
      break;
    case Opcode::FIELD: {
      const auto fields = types.fields(rt[v_[1]]);
      if (v_[2] >= fields.size())
        bad("field " + n2s(v_[2]) + " out of range for " + typeName(types, rt[v_[1]]));
      sameType(v_[0], fields[v_[2]], [&] { return "field " + n2s(v_[2]); });
      break;
    }
    case Opcode::CALL: {
      sameType(v_[0], v_[2], "the call's result type");
      std::vector<TypeId> argTypes;
      for (std::uint32_t i = 0; i < count_; ++i) argTypes.push_back(b_.registerTypes[code_[list_ + i]]);
      const BuiltinInfo* f = findBuiltin(std::uint16_t(v_[1]));
      if (f && !callTypesMatch(types, *f, argTypes, v_[2]))
        bad("the arguments or the result type do not fit the built-in " + std::string(f->name));
      break;
    }
    case Opcode::CALLF: {
      const Function& f = p_.functions[v_[1]];
      sameType(v_[0], f.result, [&] { return "the result of " + f.name; });
      args(f.params, [&] { return "function " + f.name; });
      break;
    }
    case Opcode::CALLX: {
      const Extern& e = p_.externs[v_[1]];
      sameType(v_[0], e.result, [&] { return "the result of " + e.name; });
      args(e.params, [&] { return "extern " + e.name; });
      break;
    }
    case Opcode::ACTION:
      if (!p_.predicates[v_[0]].action) bad(predText(v_[0]) + " is not an action");
      [[fallthrough]];
    case Opcode::DERIVE:
    case Opcode::SEND:
    case Opcode::SEND_DELAY:
      // Facts of thread predicates live at a thread node: only SEND_THREAD derives them.
      if (p_.predicates[v_[0]].thread) bad(predText(v_[0]) + " is a thread predicate");
      args(p_.predicates[v_[0]].fields, [&] { return predText(v_[0]); });
      break;
    case Opcode::SEND_THREAD:
      if (!p_.predicates[v_[0]].thread) bad(predText(v_[0]) + " is not a thread predicate");
      if (p_.predicates[v_[0]].action)
        bad(predText(v_[0]) + " is an action: a thread has no robot to act on");
      if (p_.types.kind(b_.registerTypes[v_[1]]) != TypeKind::Thread)
        bad("register " + n2s(v_[1]) + " is not a thread");
      args(p_.predicates[v_[0]].fields, [&] { return predText(v_[0]); });
      break;
    case Opcode::UPDATE: {
      if (v_[1] & ~std::uint32_t(kUpdateMoveToBack)) bad("unknown flag bits " + n2s(v_[1]));
      const PredId pred = needBound(v_[0]);
      if (!p_.predicates[pred].linear) bad(predText(pred) + " is not linear");
      args(p_.predicates[pred].fields, [&] { return predText(pred); });
      break;
    }
    case Opcode::AXIOMS:
      if (!isRule0) bad("outside rule 0");
      break;
    case Opcode::AXIOM_FACTS:
      axiomFacts();
      break;
    default:
      break;
  }
}

void BlockVerifier::axiomFacts() {
  if (kind_ != BlockKind::Axioms) bad("outside an axiom block");
  if (const std::string why = axiomFactsProblem(p_, code_, at_); !why.empty()) bad(why);
}

void BlockVerifier::run() {
  const TypeTable& types = p_.types;
  for (std::size_t r = 0; r < b_.registerTypes.size(); ++r)
    if (b_.registerTypes[r] >= types.size())
      blockFail("register " + n2s(r) + " has unknown type " + n2s(b_.registerTypes[r]));
  // Each loop binds a slot and takes at least 5 words, so more slots than words is nonsense, and
  // the engine sizes per-rule storage from this number.
  if (b_.slots > code_.size()) blockFail(n2s(b_.slots) + " slots for " + n2s(code_.size()) + " code words");
  if (kind_ == BlockKind::Process && b_.slots == 0) blockFail("no slot 0 for the triggering fact");
  if (function) {
    const std::size_t np = function->params.size();
    if (b_.registerTypes.size() <= np) blockFail("no result register after the " + n2s(np) + " parameters");
    for (std::size_t i = 0; i < np; ++i)
      if (b_.registerTypes[i] != function->params[i])
        blockFail("register " + n2s(i) + " does not have the parameter's type");
    if (b_.registerTypes[np] != function->result)
      blockFail("register " + n2s(np) + " does not have the result type");
  }
  if (code_.empty()) blockFail("empty code (no RET)");

  // Pass 1: instruction boundaries, so that pass 2 can check jump targets in either direction.
  start_.assign(code_.size(), false);
  std::size_t last = 0;
  starts_.clear();
  std::string why;
  for (std::size_t pos = 0; pos < code_.size();) {
    const std::size_t len = detail::instructionLength(code_, pos, why);
    if (len == 0) fail(title_() + ": word " + n2s(pos) + ": " + why);
    start_[pos] = true;
    starts_.push_back(std::uint32_t(pos));
    last = pos;
    pos += len;
  }
  if (Opcode(code_[last]) != Opcode::RET) blockFail("does not end with RET");

  // Pass 2: operands, types, loop structure.
  region_.assign(code_.size(), kTop);
  slotPred_.assign(b_.slots, Program::kNoPred);
  for (const std::uint32_t at : starts_) {
    at_ = at;
    operands();
    // An ITER belongs to the region around its loop, the NEXT to the loop it closes.
    region_[at_] = loops_.empty() ? kTop : loops_.back().at;
    semantics();
  }
  if (!loops_.empty()) {
    at_ = loops_.back().at;
    bad("loop never closed by a NEXT (exit word " + n2s(loops_.back().exit) + ")");
  }
  // A jump that leaves or enters a loop body would skip its ITER or NEXT and unbalance the
  // interpreter's loop stack.
  for (const Jump& j : jumps_)
    if (region_[j.from] != region_[j.target]) {
      at_ = j.from;
      bad("jump to word " + n2s(j.target) + " leaves or enters a loop body");
    }
  definiteAssignment();
}

// Pass 3: a register holding a string, struct, array or set is written before it is read on every
// path (an int, float, bool, node, thread or list register starts as 0 / [], a value; a null
// object pointer is not). Jumps go forward and loops nest, so one walk in order suffices: the
// state at an instruction is the intersection over the fall-through and the jumps to it, and a
// loop's exit sees the state at its ITER (no iteration).
void BlockVerifier::definiteAssignment() {
  const std::size_t nregs = b_.registerTypes.size();
  std::vector<char> needs(nregs, 0);
  bool any = false;
  for (std::size_t r = 0; r < nregs; ++r) {
    const TypeKind k = p_.types.kind(b_.registerTypes[r]);
    needs[r] = k == TypeKind::String || k == TypeKind::Struct || k == TypeKind::Array || k == TypeKind::Set;
    any = any || needs[r];
  }
  if (!any) return;
  std::vector<char> cur(nregs, 0);
  if (kind_ == BlockKind::Function)
    for (std::size_t i = 0; i < function->params.size() && i < nregs; ++i) cur[i] = 1;
  std::vector<std::vector<char>> pending(code_.size());
  auto merge = [&](std::size_t target) {
    if (pending[target].empty()) {
      pending[target] = cur;
    } else {
      for (std::size_t r = 0; r < nregs; ++r) pending[target][r] = pending[target][r] && cur[r];
    }
  };
  bool live = true;
  for (const std::uint32_t at : starts_) {
    at_ = at;
    if (!pending[at_].empty()) {
      if (live)
        for (std::size_t r = 0; r < nregs; ++r) cur[r] = cur[r] && pending[at_][r];
      else
        cur = pending[at_];
      live = true;
    }
    if (!live) continue;  // unreachable
    const auto op = Opcode(code_[at_]);
    const std::string_view letters = opcodeInfo(op).operands;
    const int written = writtenRegisterOperand(op);
    std::size_t w = at_ + 1;
    std::optional<std::size_t> writtenReg;
    for (std::size_t i = 0; i < letters.size(); ++i) {
      const char l = letters[i];
      auto read = [&](std::uint32_t r) {
        if (needs[r] && !cur[r])
          bad(regText(r) + " (" + typeName(p_.types, b_.registerTypes[r]) + ") is read before it is written");
      };
      if (l == '*') {
        for (std::uint32_t k = 0; k < code_[w]; ++k) read(code_[w + 1 + k]);
        break;
      }
      if (std::string_view("rifbnls").find(l) != std::string_view::npos) {
        if (int(i) == written)
          writtenReg = code_[w];
        else
          read(code_[w]);
      }
      if (l == 'J') merge(code_[w]);
      w += l == 'D' ? 2 : 1;
    }
    if (writtenReg) cur[*writtenReg] = 1;
    switch (op) {
      case Opcode::JMP:
      case Opcode::NEXT:
      case Opcode::FIRE:
      case Opcode::CFIRE:
      case Opcode::RET:
        live = false;
        break;
      default:
        break;
    }
  }
}

void checkType(const Program& p, TypeId t, const std::string& what) {
  if (t >= p.types.size()) fail(what + " has unknown type " + n2s(t));
}

// The predicates the VM itself stores facts of (§4.1.3, §6.2, §6.12) must have the shape it
// writes: `_init` and `_init_thread` linear without arguments, `thread-list` a persistent list of
// threads, `leader-thread` a persistent thread.
void checkSpecialPredicates(const Program& p) {
  auto check = [&](PredId id, const char* name, bool linear, bool thread, std::vector<TypeId> fields) {
    if (id == Program::kNoPred || id >= p.predicates.size()) return;
    const PredicateDesc& d = p.predicates[id];
    if (d.linear != linear || d.action || d.thread != thread || d.fields != fields)
      fail(std::string("predicate ") + n2s(id) + " (" + d.name + "): the VM stores " + name +
           " facts, which this declaration does not fit");
  };
  check(p.initPredicate, "_init", true, false, {});
  const PredId initThread = p.predicates.find("_init_thread");
  if (initThread < p.predicates.size() && p.predicates[initThread].thread)
    check(initThread, "_init_thread", true, true, {});
  const PredId list = p.predicates.find("thread-list");
  if (list < p.predicates.size() && p.predicates[list].thread) {
    const PredicateDesc& d = p.predicates[list];
    if (d.linear || d.action || d.fields.size() != 1 || p.types.kind(d.fields[0]) != TypeKind::List ||
        p.types.element(d.fields[0]) != TypeTable::kThread)
      fail("predicate " + n2s(list) +
           " (thread-list): the VM stores thread-list facts, which this declaration does not fit");
  }
  const PredId leader = p.predicates.find("leader-thread");
  if (leader < p.predicates.size() && p.predicates[leader].thread)
    check(leader, "leader-thread", false, true, {TypeTable::kThread});
}

}  // namespace

void verifyProgram(const Program& p) {
  const std::size_t np = p.predicates.size();
  if (p.initPredicate != Program::kNoPred && p.initPredicate >= np)
    fail("init predicate " + n2s(p.initPredicate) + " is not a predicate");
  checkSpecialPredicates(p);
  for (const Global& g : p.globals) checkType(p, g.type, "global " + g.name);
  for (const Function& f : p.functions) {
    for (TypeId t : f.params) checkType(p, t, "a parameter of function " + f.name);
    checkType(p, f.result, "the result of function " + f.name);
  }
  for (const Extern& e : p.externs) {
    for (TypeId t : e.params) checkType(p, t, "a parameter of extern " + e.name);
    checkType(p, e.result, "the result of extern " + e.name);
  }
  for (std::size_t i = 0; i < p.rules.size(); ++i)
    for (PredId b : p.rules[i].bodyPredicates)
      if (b >= np)
        fail(titled("rule " + n2s(i), p.rules[i].block.label) + ": unknown body predicate " + n2s(b));
  for (std::size_t i = 0; i < p.processes.size(); ++i)
    if (p.processes[i].trigger >= np)
      fail(titled("process " + n2s(i), p.processes[i].block.label) + ": unknown trigger predicate " +
           n2s(p.processes[i].trigger));
  if (p.nodeAxioms.size() != p.nodeSourceIds.size())
    fail(n2s(p.nodeAxioms.size()) + " axiom entries for " + n2s(p.nodeSourceIds.size()) + " nodes");
  for (std::size_t n = 0; n < p.nodeAxioms.size(); ++n)
    if (p.nodeAxioms[n] != Program::kNoAxioms && p.nodeAxioms[n] >= p.axiomBlockCount())
      fail("node " + n2s(n) + ": unknown axiom block " + n2s(p.nodeAxioms[n]));
  if (p.scheduling.order != PriorityOrder::Desc && p.scheduling.order != PriorityOrder::Asc)
    fail("unknown priority order");
  for (const IndexRequest& ix : p.indexes) {
    if (ix.predicate >= np) fail("index on unknown predicate " + n2s(ix.predicate));
    if (ix.field >= p.predicates[ix.predicate].arity())
      fail("index on field " + n2s(ix.field) + " of " + p.predicates[ix.predicate].name + ", which has " +
           n2s(p.predicates[ix.predicate].arity()) + " fields");
  }

  VerifierScratch scratch;
  BlockVerifier(
      p, p.globalsInit, BlockKind::Globals, [] { return std::string("globals"); }, scratch)
      .run();
  for (std::size_t i = 0; i < p.functions.size(); ++i) {
    BlockVerifier v(
        p, p.functions[i].block, BlockKind::Function,
        [&, i] { return "function " + n2s(i) + " (" + p.functions[i].name + ")"; }, scratch);
    v.function = &p.functions[i];
    v.run();
  }
  for (std::size_t i = 0; i < p.rules.size(); ++i) {
    BlockVerifier v(
        p, p.rules[i].block, BlockKind::Rule,
        [&, i] { return titled("rule " + n2s(i), p.rules[i].block.label); }, scratch);
    v.isRule0 = i == 0;
    v.run();
  }
  for (std::size_t i = 0; i < p.processes.size(); ++i) {
    const Process& pr = p.processes[i];
    BlockVerifier v(
        p, pr.block, BlockKind::Process,
        [&, i] {
          return titled("process " + n2s(i) + " on " + p.predicates[pr.trigger].name, pr.block.label);
        },
        scratch);
    v.process = &pr;
    v.run();
  }
  for (std::size_t i = 0; i < p.axiomBlocks.size(); ++i)
    BlockVerifier(
        p, p.axiomBlocks[i], BlockKind::Axioms,
        [&, i] { return titled("axioms " + n2s(i), p.axiomBlocks[i].label); }, scratch)
        .run();
  for (std::size_t i = 0; i < p.literalAxioms.size(); ++i) verifyLiteralAxioms(p, i);
}

}  // namespace meldvm
