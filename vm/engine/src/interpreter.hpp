// The bytecode interpreter: runs one code block (a rule, a persistent process, an axiom block, a
// function, the globals initialiser) at a node. Loops are run by recursion on ITER so that the
// nested-loop matching of spec §6.4.3 reads directly: a loop body returns "fired" or "not fired",
// and a loop flagged kIterReturnOnFire stops after its body fired.
//
// Registers live in chunks that never move (a frame keeps a plain pointer to its registers while
// nested frames are pushed). Consumed linear facts are only marked during a rule run (the Machine
// unlinks them afterwards), so every loop can step to its successor after its body ran.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <memory>
#include <new>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "meldvm/builtins.hpp"
#include "meldvm/database.hpp"
#include "meldvm/derivation_log.hpp"
#include "meldvm/native_abi.h"
#include "meldvm/program.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

class Machine;
class NativeCode;

class Interpreter {
 public:
  // native: entry points of native code for some blocks (they run natively), or nullptr.
  Interpreter(Machine& machine, const Program& program, Database& db, BuiltinContext& ctx,
              const NativeCode* native = nullptr);
  ~Interpreter();

  // Runs a block at node `host`. `trigger` (process blocks): the arguments slot 0 is bound to.
  // `negative`: the retraction mode of the persistent processes (§6.8).
  void run(const CodeBlock& block, NodeId host, bool negative = false, PredId triggerPred = 0,
           const Value* trigger = nullptr);
  // Runs rule `rule`'s block: its BlockInfo found by number, not by hashing the block's address.
  // (Inline: rule runs are short; heat-transfer 20 x 20 makes 162 K of them for 537 K facts derived.)
  void runRule(std::uint32_t rule, NodeId host) {
    RuleRun& r = rules_[rule];
    if (!r.info) [[unlikely]]
      prepareRule(rule, r);
    if (r.regs && !r.running)
      runInOwnFrame(r, host);
    else
      runWith(program_.rules[rule].block, *r.info, host, false, 0, nullptr);
  }

 private:
  struct Slot {
    PredId pred;
    NodeId node;  // where the fact is stored: the host, or the thread node (kIterThread)
    FactRef fact;
    std::uint32_t flags;
    const Value* fixed;  // pre-bound arguments (process trigger) instead of a stored fact
  };
  struct Frame {
    const CodeBlock* block;
    const std::uint32_t* code;
    Value* regs;
    Slot* slots;
    const std::uint8_t* boxed;      // per register: its type is boxed
    const std::uint8_t* slotFlags;  // per slot: kSlotAliased, kSlotMovesLists, kSlotWalksLists
    NodeId host;
    bool negative;
    bool updated = false;  // an UPDATE ran in this block (RET_IF_UPDATED)
    // Bit s: a loop that consumes binds slot s (all bits for a block of more than 64 slots).
    std::uint64_t consumingSlots = 0;
  };
  enum class Status : std::uint8_t { NotFired, Fired, Return };

  Status exec(Frame& f, std::uint32_t pc);
  // A loop instruction decoded, its slot bound to the predicate and node and the loop counted.
  struct LoopHead {
    Opcode op;
    PredId pred;
    std::uint32_t slot, flags, body, keyField;
    Value key;  // ITER_KEY
    NodeId at;  // the host, or the thread's node
  };
  [[gnu::always_inline]] LoopHead beginLoop(Frame& f, std::uint32_t pc);
  // A loop that exec runs in place (runsInPlace): its slot, its fact and what it counted so far.
  struct OpenLoop {
    static constexpr std::uint32_t kPlain = ~0u;  // index: a plain ITER
    FactRef fact;
    PredId pred;
    std::uint32_t slot, body, after, index;
    std::uint64_t tried;
    bool linear, returnOnFire, fired;
  };
  static constexpr std::uint32_t kOpenLoops = 12;  // deeper loops go through loop()
  [[gnu::always_inline]] bool runsInPlace(const Frame& f, const std::uint32_t* c) const;
  [[gnu::always_inline]] bool openLoop(Frame& f, std::uint32_t pc, OpenLoop& l);
  [[gnu::always_inline]] FactRef nextInLoop(const OpenLoop& l, FactRef fact) const;
  [[gnu::always_inline]] bool visitFrom(Frame& f, OpenLoop& l, FactRef fact);
  [[gnu::always_inline]] bool visitNext(Frame& f, OpenLoop& l, Status st);
  // The loop instruction at pc; runBody(bodyPc) runs its body once the slot is bound.
  template <class RunBody>
  [[gnu::noinline]] bool loop(Frame& f, std::uint32_t pc, RunBody&& runBody);  // kept out of exec
  // One straight-on instruction with opcode OP (straight_ops.inc), for native code.
  template <Opcode OP>
  void step(Frame& f, std::uint32_t pc);
  // The block's entry: native code when there is, else the interpreter from pc 0.
  Status start(Frame& f, meld_native_block native);
  friend struct NativeHelpers;  // native_abi.h's helpers (interpreter.cpp): this class's code
  void ruleFired();             // a FIRE: the machine's count of rules fired
  // Whether a linear loop passes over a fact: consumed, or bound by an enclosing loop (§6.4.3;
  // only a slot that may hold a fact of the same predicate can).
  [[gnu::always_inline]] bool skipFact(const Frame& f, std::uint32_t slot, PredId p, FactRef fact) const {
    return db_.consumedMark(p, fact) ||
           ((f.slotFlags[slot] & kSlotAliased) && boundOutside(f, slot, p, fact));
  }
  bool boundOutside(const Frame& f, std::uint32_t slot, PredId p, FactRef fact) const;
  // The rule fired: consume the linear facts bound from firstSlot on (inline: a persistent rule's
  // firing consumes nothing and should cost next to nothing).
  [[gnu::always_inline]] void fire(Frame& f, std::uint32_t firstSlot) {
    const std::uint64_t all = f.consumingSlots;  // only those slots are looked at
    if (!all) return;
    if (firstSlot < 64)
      for (std::uint64_t m = all & ~std::uint64_t(0) << firstSlot; m; m &= m - 1) {
        const Slot& sl = f.slots[std::countr_zero(m)];
        if (consumable(sl)) consumeSlot(sl);
      }
    if (all == ~std::uint64_t(0)) [[unlikely]]  // (a block of more than 64 slots: those past 64)
      fireFromSlot64(f, firstSlot);
  }
  void fireFromSlot64(Frame& f, std::uint32_t firstSlot) {
    for (std::uint32_t s = std::max<std::uint32_t>(firstSlot, 64); s < f.block->slots; ++s)
      if (consumable(f.slots[s])) consumeSlot(f.slots[s]);
  }
  // Whether FIRE consumes the fact of this slot: its loop consumes, and it is not consumed yet.
  [[gnu::always_inline]] bool consumable(const Slot& sl) const {
    return (sl.flags & kIterConsume) && sl.fact != kNoFact && !sl.fixed &&
           !db_.consumedMark(sl.pred, sl.fact);
  }
  void consumeSlot(const Slot& sl);  // inline, in interpreter.cpp (where Machine is complete)
  // DERIVE, SEND (and SEND_DELAY) and UPDATE once their arguments are gathered, also inline there:
  // the interpreter's cases and the helpers of native code, which gathers the arguments itself.
  [[gnu::always_inline]] void deriveFact(const Frame& f, std::uint32_t pc, PredId p, const Value* args);
  [[gnu::always_inline]] void sendFact(const Frame& f, std::uint32_t pc, PredId p, NodeId dest,
                                       const Value* args, std::uint32_t delayMs);
  [[gnu::always_inline]] void updateFact(Frame& f, std::uint32_t pc, std::uint32_t slot, bool moveToBack,
                                         const Value* args);
  // AXIOM_FACTS at pc (verified: whole facts of its predicate, every field an int, float, bool or
  // node), decoded and derived: together (Machine::deriveEach) unless derivations are recorded or
  // the block runs negated; note(pc, args) before each fact's derivation then.
  void axiomFacts(const Frame& f, std::uint32_t pc);
  void axiomFactsTogether(const std::uint32_t* instruction, NodeId host);
  template <class Note>
  void axiomFactsOneByOne(const std::uint32_t* code, std::uint32_t pc, NodeId host, bool negative,
                          Note&& note);
  // Block i of the program's LiteralAxioms, for the AXIOMS of `host`.
  void runLiteralAxioms(std::size_t i, NodeId host);
  Derivation derivation(bool axiom, std::string_view label, std::span<const SourceLine> lines,
                        std::uint32_t pc, NodeId host) const;
  void record(Derivation d, NodeId node, PredId p, const Value* args);
  // Why a fact exists (DerivationLog): the rule's line and the facts its slots hold.
  [[gnu::noinline]] void noteDerivation(const Frame& f, std::uint32_t pc, NodeId node, PredId p,
                                        const Value* args);
  const Value* slotArgs(const Frame& f, std::uint32_t s) const {
    const Slot& sl = f.slots[s];
    return sl.fixed ? sl.fixed : db_.args(sl.pred, sl.fact);
  }
  [[gnu::always_inline]] void setReg(Frame& f, std::uint32_t r, Value v) {  // takes ownership of v
    if (f.boxed[r]) heap_.releaseObject(f.regs[r]);  // f.boxed: the register's type is boxed
    f.regs[r] = v;
  }
  Value retained(const Frame& f, std::uint32_t r) const;
  // TEST: whether field c[2] of the fact in slot c[1] equals register c[3].
  [[gnu::always_inline]] bool testField(const Frame& f, const std::uint32_t* c) const {
    const TypeId t = program_.predicates[f.slots[c[1]].pred].fields[c[2]];
    return valuesEqualFast(program_.types, t, slotArgs(f, c[1])[c[2]], f.regs[c[3]]);
  }
  Value callFunction(std::uint32_t fn, const Value* args, NodeId host);
  // The registers' values in args_ (no references taken); valid until the next gatherArgs.
  [[gnu::always_inline]] std::span<const Value> gatherArgs(const Frame& f, const std::uint32_t* regs,
                                                           std::uint32_t count) {
    if (count > args_.size()) growArgs(count);
    Value* out = args_.data();
    for (std::uint32_t i = 0; i < count; ++i) out[i] = f.regs[regs[i]];
    return {out, count};
  }
  [[gnu::noinline]] void growArgs(std::uint32_t count) { args_.resize(count); }

  // Frames: registers and slots from chunks that never move.
  struct Alloc {
    Value* regs;
    Slot* slots;
    std::size_t regMark, slotMark;
  };
  struct BlockInfo {
    std::uint64_t consumingSlots = 0;      // Frame::consumingSlots (blockFlags)
    std::vector<std::uint8_t> boxed;       // blockFlags
    std::vector<std::uint8_t> slotFlags;   // Frame::slotFlags (blockFlags)
    std::vector<std::uint32_t> boxedRegs;  // the boxed registers, which leave() releases
    meld_native_block native = nullptr;
  };
  Alloc enter(const CodeBlock& b);
  void leave(const Frame& f, const Alloc& a, const BlockInfo& info);
  // A frame as a block's run begins (registers zero, slots unbound) and as it ends (the boxed
  // registers' references let go): enter/leave's frames and a rule's own (runInOwnFrame).
  static void clearFrame(Value* regs, std::size_t regCount, Slot* slots, std::size_t slotCount) {
    std::fill(regs, regs + regCount, Value());
    for (std::size_t s = 0; s < slotCount; ++s) slots[s] = Slot{0, 0, kNoFact, 0, nullptr};
  }
  void releaseBoxedRegs(const Frame& f, const BlockInfo& info) {
    for (std::uint32_t r : info.boxedRegs) heap_.releaseObject(f.regs[r]);
  }
  const BlockInfo& infoOf(const CodeBlock& b);
  void runWith(const CodeBlock& block, const BlockInfo& info, NodeId host, bool negative, PredId triggerPred,
               const Value* trigger);
  void blockFlags(const CodeBlock& b, BlockInfo& info, bool scanLoops) const;
  void aliasedSlots(const CodeBlock& b, BlockInfo& info) const;
  void listReadingLoops(const CodeBlock& b, BlockInfo& info) const;
  // Frame::slotFlags: an earlier slot may hold a fact of the slot's predicate; the slot's loop
  // (over a linear predicate with a list field) moves that list on, or hands it to a function
  // (detail::listFetchDepth).
  // kSlotListsStayPut: its loop walks lists that stay put (detail::listsStayPut, ListPipeline).
  static constexpr std::uint8_t kSlotAliased = 1, kSlotMovesLists = 2, kSlotWalksLists = 4,
                                kSlotListsStayPut = 8;

  Machine& machine_;
  const Program& program_;
  Database& db_;
  Heap& heap_;
  BuiltinContext& ctx_;
  std::uint32_t depth_ = 0;         // nested function calls
  const char* stackTop_ = nullptr;  // a local of the outermost call, for the stack budget

  // Register and slot chunks are raw storage: enter() writes what a block uses before it runs, so
  // the first 512 KiB of registers are not zeroed (and faulted in) at start, which was a fifth of
  // a tiny program's instructions.
  struct RawDelete {
    void operator()(void* p) const noexcept { ::operator delete(p); }
  };
  template <class T>
  using Chunk = std::unique_ptr<T[], RawDelete>;
  template <class T>
  static Chunk<T> rawChunk(std::size_t n) {
    return Chunk<T>(static_cast<T*>(::operator new(n * sizeof(T))));
  }
  std::vector<Chunk<Value>> regChunks_;
  std::vector<Chunk<Slot>> slotChunks_;
  std::size_t regChunk_ = 0, regUsed_ = 0, slotChunk_ = 0, slotUsed_ = 0;
  const NativeCode* native_;
  // What native code's `vm` points at (native_abi.h): it begins and ends plain loops from it.
  meld_native_context nativeContext_{};
  meld_native_heap nativeHeap_{};  // where native code takes list cells (nativeContext_.heap)
  std::vector<meld_native_table> nativeTables_;
  // Each table's meld_native_table::fields (empty: the table has no index).
  std::vector<std::vector<meld_native_field_index>> nativeFieldIndexes_;
  void setUpNativeContext();
  void setUpNativeBuffers(meld_native_context& c);  // the sent and derived facts' arrays
  static bool describeIndexes(const FactTable& t, std::vector<meld_native_field_index>& fields);
  std::unordered_map<const CodeBlock*, BlockInfo> blocks_;
  // A rule's block info, found by number (into blocks_, whose entries never move), and the
  // registers and slots it keeps between its runs: rules never nest, so a rule's frame needs none
  // of the chunk stack's bookkeeping (enter/leave was a fifth of the VM's own instructions per
  // native rule run of heat-transfer; the bytecode's runs of it, 3.6 % fewer instructions).
  struct RuleRun {
    const BlockInfo* info = nullptr;
    Chunk<Value> regs;  // null: too large a block, run by runWith (which reports it)
    Chunk<Slot> slots;
    std::uint32_t regCount = 0, slotCount = 0;
    bool running = false;  // (were a rule ever run inside its own run, the inner one takes the chunk stack)
    Frame frame{};         // set once; a run sets its host and clears `updated` (`negative` stays false)
  };
  std::vector<RuleRun> rules_;  // one per rule, from the start
  void prepareRule(std::uint32_t rule, RuleRun& r);
  // What runWith does, less the chunk stack: the frame is the rule's own, written afresh as
  // enter() writes one (registers zero, slots unbound), its block run (native code, else the
  // interpreter) and its boxed registers released after the run. (Inline, into the Machine's loop
  // over a node's rules, Machine::runOnce.)
  void runInOwnFrame(RuleRun& r, NodeId host) {
    Value* regs = r.regs.get();
    clearFrame(regs, r.regCount, r.slots.get(), r.slotCount);
    const BlockInfo& info = *r.info;
    Frame& f = r.frame;
    f.host = host;
    f.updated = false;
    r.running = true;
    try {
      if (info.native)
        info.native(nativeHelpers_, reinterpret_cast<meld_native_vm*>(&nativeContext_),
                    reinterpret_cast<meld_native_frame*>(&f), reinterpret_cast<std::uint64_t*>(regs));
      else
        exec(f, 0);
    } catch (...) {
      releaseBoxedRegs(f, info);
      r.running = false;
      throw;
    }
    releaseBoxedRegs(f, info);
    r.running = false;
  }
  static const meld_native_helpers* helperTable();  // NativeHelpers::kTable (interpreter.cpp)
  const meld_native_helpers* nativeHelpers_ = nullptr;
  BlockInfo axiomInfo_;                     // infoOf an axiom block (not cached)
  const CodeBlock* lastBlock_ = nullptr;    // the processes of a program run the same few blocks
  const BlockInfo* lastInfo_ = nullptr;
  std::vector<Value> args_;      // arguments gathered for DERIVE/SEND/CALL (grows, never shrinks)
  std::vector<FactRef> sorted_;  // ITER_SORTED candidates (a stack of runs)
};

}  // namespace meldvm
