#include "interpreter.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "list_pipeline.hpp"
#include "meldvm/arith.hpp"
#include "meldvm/bytecode_internal.hpp"
#include "meldvm/derivation_log.hpp"
#include "meldvm/dump.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/native_code.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

inline void Interpreter::consumeSlot(const Slot& sl) { machine_.consumed(sl.node, sl.pred, sl.fact); }

inline void Interpreter::deriveFact(const Frame& f, std::uint32_t pc, PredId p, const Value* args) {
  if (machine_.derivations_ && !f.negative) [[unlikely]]
    noteDerivation(f, pc, f.host, p, args);
  machine_.derive(f.host, p, args, f.negative);
}

inline void Interpreter::sendFact(const Frame& f, std::uint32_t pc, PredId p, NodeId dest, const Value* args,
                                  std::uint32_t delayMs) {
  if (machine_.derivations_ && !f.negative) [[unlikely]]
    noteDerivation(f, pc, dest, p, args);
  machine_.send(f.host, dest, p, args, f.negative, delayMs);
}

inline void Interpreter::updateFact(Frame& f, std::uint32_t pc, std::uint32_t slot, bool moveToBack,
                                    const Value* args) {
  const Slot& sl = f.slots[slot];
  if (machine_.derivations_ && !f.negative) [[unlikely]]
    noteDerivation(f, pc, sl.node, sl.pred, args);
  if (!f.negative) machine_.updated(sl.node, sl.pred, sl.fact, args, moveToBack);
  f.updated = true;
}

namespace {
constexpr std::size_t kRegChunk = 1 << 16;
constexpr std::size_t kSlotChunk = 1 << 12;
// Nested `fun` calls recurse on the C++ stack: stop before the usual 8 MiB of the main thread are
// used up (a sanitized build takes several times more stack per call than an optimized one).
constexpr std::ptrdiff_t kMaxCallStackBytes = std::ptrdiff_t(6) << 20;

double immDouble(const std::uint32_t* c) {
  const std::uint64_t bits = std::uint64_t(c[0]) | (std::uint64_t(c[1]) << 32);
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
}  // namespace

Interpreter::Interpreter(Machine& machine, const Program& program, Database& db, BuiltinContext& ctx,
                         const NativeCode* native)
    : machine_(machine), program_(program), db_(db), heap_(db.heap()), ctx_(ctx), native_(native) {
  regChunks_.push_back(rawChunk<Value>(kRegChunk));
  slotChunks_.push_back(rawChunk<Slot>(kSlotChunk));
  args_.resize(64);
  rules_.resize(program_.rules.size());
  if (native_) setUpNativeContext();
  nativeHelpers_ = helperTable();
}

Interpreter::~Interpreter() = default;

// The Machine requested its indexes before it made its interpreter: the tables' layouts are final.
void Interpreter::setUpNativeContext() {
  static_assert(offsetof(Frame, slots) == offsetof(meld_native_frame_head, slots) &&
                offsetof(Frame, host) == offsetof(meld_native_frame_head, host) &&
                offsetof(Frame, negative) == offsetof(meld_native_frame_head, negative) &&
                offsetof(Frame, updated) == offsetof(meld_native_frame_head, updated) && sizeof(bool) == 1 &&
                sizeof(NodeId) == sizeof(std::uint32_t));
  static_assert(sizeof(ListHead) == 4 * MELD_NATIVE_HEAD_WORDS && offsetof(ListHead, first) == 0 &&
                NodeHeads::kShift == MELD_NATIVE_HEAD_PAGE_SHIFT);
  static_assert(sizeof(machine_.stepsLeft_) == 8 && sizeof(machine_.stats_.factsTried) == 8);
  for (PredId p = 0; p < program_.predicates.size(); ++p) {
    FactTable& t = db_.tableForNativeCode(p);
    const bool buffered = machine_.tables_.plainLinear[p] && !db_.holdsReferences(p);
    const bool bufferedBoxed = machine_.tables_.plainLinear[p] && db_.referenceFields(p).objectsOnly();
    const PredicateDesc& d = program_.predicates[p];
    const bool persistentSent = !d.linear && !d.action && !d.thread && !db_.holdsReferences(p);
    static_assert(sizeof(FactRef) == sizeof(std::uint32_t));
    const bool keyed = describeIndexes(t, nativeFieldIndexes_.emplace_back());
    nativeTables_.push_back(
        {reinterpret_cast<const std::uint64_t* const*>(t.slotArrayAddress()), t.stride(), t.argOffset(),
         (t.plainWords() ? MELD_NATIVE_TABLE_PLAIN : 0u) | (buffered ? MELD_NATIVE_TABLE_BUFFERED : 0u) |
             (persistentSent ? MELD_NATIVE_TABLE_PERSISTENT_SENT : 0u) |
             (bufferedBoxed ? MELD_NATIVE_TABLE_BUFFERED_BOXED : 0u) | (keyed ? MELD_NATIVE_TABLE_KEYED : 0u),
         0, t.freeListAddress(), t.liveAddress(),
         nativeFieldIndexes_.back().empty() ? nullptr : nativeFieldIndexes_.back().data()});
  }
  static_assert(std::is_same_v<std::size_t, std::uint64_t>, "meld_native_heap's counts are the heap's");
  const Heap::CellAllocation cells = heap_.cellAllocationForNativeCode();
  nativeHeap_ = {cells.freeList, cells.bump, cells.bumpEnd, cells.live, cells.bytesInUse};
  meld_native_context& c = nativeContext_;
  c.interpreter = this;
  c.heap = &nativeHeap_;
  static_assert(sizeof(Value) == sizeof(std::uint64_t));
  c.globals = reinterpret_cast<const std::uint64_t*>(machine_.globals_.data());  // sized before this
  c.tables = nativeTables_.data();
  c.head_pages = reinterpret_cast<const std::uint32_t* const* const*>(db_.nodeHeads().pageTableAddress());
  c.heads_per_node = db_.nodeHeads().headsPerNode();
  c.steps_left = &machine_.stepsLeft_;
  c.facts_tried = &machine_.stats_.factsTried;
  c.stop = reinterpret_cast<const std::uint8_t*>(&machine_.stop_);
  c.shared_stop = reinterpret_cast<const std::uint8_t*>(machine_.stopFlag_);  // (noStop_ when alone)
  c.consumed = machine_.consumed_.forNativeCode();
  static_assert(sizeof(machine_.stats_.factsConsumed) == 8 && sizeof(machine_.runConsumed_) == 8 &&
                sizeof(machine_.stats_.rulesFired) == 8);
  c.facts_consumed = &machine_.stats_.factsConsumed;
  c.run_consumed = &machine_.runConsumed_;
  c.rules_fired = &machine_.stats_.rulesFired;
  static_assert(sizeof(machine_.stats_.factsDerived) == 8 && sizeof(machine_.runDerived_) == 8);
  c.derivations = reinterpret_cast<const void* const*>(&machine_.derivations_);
  c.candidates = &machine_.candidatesData_;
  c.facts_derived = &machine_.stats_.factsDerived;
  c.run_derived = &machine_.runDerived_;
  c.rule_words = machine_.tables_.ruleWords;
  setUpNativeBuffers(c);
}

// A table's indexes as native code sees them (meld_native_table::fields, one per argument);
// whether they make it MELD_NATIVE_TABLE_KEYED (every index on one argument of its own, facts
// native code may write).
bool Interpreter::describeIndexes(const FactTable& t, std::vector<meld_native_field_index>& fields) {
  if (t.indexCount() == 0) return false;
  fields.assign(t.arity(), meld_native_field_index{nullptr, nullptr, nullptr, 0, 0});
  bool keyed = t.wordsUnderIndexes();
  for (std::uint32_t x = 0; x < t.indexCount(); ++x) {
    const FactTable::KeySpec key = t.indexKey(x);
    if (key.count != 1 || fields[key.first].link_word != 0) {
      keyed = false;  // a key of several arguments, or a second index on the same one
      continue;
    }
    const SlotHash& heads = t.indexHeads(x);
    fields[key.first] = {heads.entriesAddress(), heads.maskAddress(), heads.sizeAddress(),
                         FactTable::indexLinkWord(x), t.integerIndex(x) ? 1u : 0u};
  }
  return keyed;
}

void Interpreter::setUpNativeBuffers(meld_native_context& c) {
  using Sent = Machine::PendingFact;
  static_assert(sizeof(Sent) == sizeof(meld_native_sent_fact) &&
                offsetof(Sent, pred) == offsetof(meld_native_sent_fact, pred) &&
                offsetof(Sent, negative) == offsetof(meld_native_sent_fact, negative) &&
                offsetof(Sent, args) == offsetof(meld_native_sent_fact, args) &&
                offsetof(Sent, delayMs) == offsetof(meld_native_sent_fact, delay_ms) &&
                offsetof(Sent, cancelled) == offsetof(meld_native_sent_fact, cancelled));
  using SentState = NativeArray<Sent>::State;
  using ArgsState = ValueBuffer::State;
  static_assert(sizeof(SentState) == sizeof(meld_native_array) &&
                sizeof(ArgsState) == sizeof(meld_native_array) &&
                offsetof(SentState, size) == offsetof(meld_native_array, size) &&
                offsetof(ArgsState, size) == offsetof(meld_native_array, size) &&
                offsetof(SentState, capacity) == offsetof(meld_native_array, capacity) &&
                offsetof(ArgsState, capacity) == offsetof(meld_native_array, capacity));
  static_assert(sizeof(machine_.ownGraphSerial_) == 1 && sizeof(machine_.stats_.factsSent) == 8);
  c.sends_buffered = reinterpret_cast<const std::uint8_t*>(&machine_.ownGraphSerial_);
  c.live_below = db_.liveBelowAddress();
  c.sent = reinterpret_cast<meld_native_array*>(machine_.sentLinear_.forNativeCode());
  c.sent_args = reinterpret_cast<meld_native_array*>(machine_.sentArgs_.forNativeCode());
  c.facts_sent = &machine_.stats_.factsSent;
  c.derived = reinterpret_cast<meld_native_array*>(machine_.linearOut_.forNativeCode());
  c.derived_args = reinterpret_cast<meld_native_array*>(machine_.linearOutArgs_.forNativeCode());
  c.sent_persistent = reinterpret_cast<meld_native_array*>(machine_.sentPersistent_.forNativeCode());
}

// Per register whether it is boxed, then whether any loop consumes its fact (fire() has nothing
// to do otherwise); and the boxed registers in a list, which leave() releases.
void Interpreter::blockFlags(const CodeBlock& b, BlockInfo& info, bool scanLoops) const {
  const std::size_t regs = b.registerTypes.size();
  std::vector<std::uint8_t>& v = info.boxed;
  v.assign(regs, 0);
  info.consumingSlots = 0;
  info.boxedRegs.clear();
  for (std::size_t r = 0; r < regs; ++r) {
    v[r] = program_.types.boxed(b.registerTypes[r]);
    if (v[r]) info.boxedRegs.push_back(std::uint32_t(r));
  }
  info.slotFlags.assign(b.slots, 0);
  if (!scanLoops) return;
  detail::forEachInstruction(b.code, [&](std::size_t pc) {
    if (detail::isLoop(b.code[pc]) && (b.code[pc + 3] & kIterConsume))
      info.consumingSlots |= b.slots > 64 ? ~std::uint64_t(0) : std::uint64_t(1) << b.code[pc + 2];
  });
  aliasedSlots(b, info);
  listReadingLoops(b, info);
}

// A slot is aliased when an earlier slot may hold a fact of its predicate: both bound by loops of
// the same predicate, or either bound by loops of several predicates, or by a persistent process's
// trigger (slot 0, any predicate). Only an aliased slot's loop looks for its fact in the others.
void Interpreter::aliasedSlots(const CodeBlock& b, BlockInfo& info) const {
  constexpr std::int64_t kUnbound = -2, kAny = -1;
  std::vector<std::int64_t> pred(b.slots, kUnbound);
  detail::forEachInstruction(b.code, [&](std::size_t pc) {
    if (!detail::isLoop(b.code[pc])) return;
    std::int64_t& p = pred[b.code[pc + 2]];
    p = p == kUnbound || p == b.code[pc + 1] ? std::int64_t(b.code[pc + 1]) : kAny;
  });
  for (const Process& process : program_.processes)
    if (&process.block == &b && b.slots > 0) pred[0] = kAny;
  for (std::size_t s = 0; s < b.slots; ++s)
    for (std::size_t outer = 0; outer < s; ++outer)
      if (pred[outer] != kUnbound && (pred[outer] == kAny || pred[s] == kAny || pred[outer] == pred[s])) {
        info.slotFlags[s] |= kSlotAliased;
        break;
      }
}

// The loops that fetch the lists of the facts ahead (walkListsAhead, detail::listFetchDepth).
void Interpreter::listReadingLoops(const CodeBlock& b, BlockInfo& info) const {
  int stayPut = -1;  // detail::listsStayPut, worked out once for the block
  detail::forEachInstruction(b.code, [&](std::size_t pc) {
    const int depth = detail::listFetchDepth(program_, b.code, pc);
    if (depth >= 0 && b.code[pc + 2] < b.slots)
      info.slotFlags[b.code[pc + 2]] |= depth > 0 ? kSlotWalksLists : kSlotMovesLists;
    if (depth > 0 && b.code[pc + 2] < b.slots &&
        (stayPut < 0 ? (stayPut = detail::listsStayPut(b.code)) : stayPut))
      info.slotFlags[b.code[pc + 2]] |= kSlotListsStayPut;
  });
}

const Interpreter::BlockInfo& Interpreter::infoOf(const CodeBlock& b) {
  if (&b == lastBlock_) return *lastInfo_;
  const auto& axioms = program_.axiomBlocks;
  if (!axioms.empty() && &b >= axioms.data() && &b < axioms.data() + axioms.size()) {
    // An axiom block runs once: no cache entry (a big program has millions of them), and no
    // native code. Axiom blocks are straight-line code (no loops) and never nest, so one scratch
    // serves them all.
    blockFlags(b, axiomInfo_, false);
    return axiomInfo_;
  }
  auto it = blocks_.find(&b);
  if (it == blocks_.end()) {
    BlockInfo info;
    blockFlags(b, info, true);
    if (native_) info.native = native_->find(b);
    it = blocks_.emplace(&b, std::move(info)).first;
  }
  lastBlock_ = &b;
  lastInfo_ = &it->second;
  return it->second;
}

Interpreter::Alloc Interpreter::enter(const CodeBlock& b) {
  const std::size_t regs = b.registerTypes.size(), slots = b.slots;
  if (regs > kRegChunk || slots > kSlotChunk) throw RuntimeError("code block '" + b.label + "' is too large");
  Alloc a{nullptr, nullptr, regChunk_ * kRegChunk + regUsed_, slotChunk_ * kSlotChunk + slotUsed_};
  if (regUsed_ + regs > kRegChunk) {
    if (++regChunk_ == regChunks_.size()) regChunks_.push_back(rawChunk<Value>(kRegChunk));
    regUsed_ = 0;
  }
  if (slotUsed_ + slots > kSlotChunk) {
    if (++slotChunk_ == slotChunks_.size()) slotChunks_.push_back(rawChunk<Slot>(kSlotChunk));
    slotUsed_ = 0;
  }
  a.regs = regChunks_[regChunk_].get() + regUsed_;
  a.slots = slotChunks_[slotChunk_].get() + slotUsed_;
  regUsed_ += regs;
  slotUsed_ += slots;
  clearFrame(a.regs, regs, a.slots, slots);
  return a;
}

void Interpreter::leave(const Frame& f, const Alloc& a, const BlockInfo& info) {
  releaseBoxedRegs(f, info);
  regChunk_ = a.regMark / kRegChunk;
  regUsed_ = a.regMark % kRegChunk;
  slotChunk_ = a.slotMark / kSlotChunk;
  slotUsed_ = a.slotMark % kSlotChunk;
}

void Interpreter::run(const CodeBlock& block, NodeId host, bool negative, PredId triggerPred,
                      const Value* trigger) {
  runWith(block, infoOf(block), host, negative, triggerPred, trigger);
}

void Interpreter::prepareRule(std::uint32_t rule, RuleRun& r) {
  const CodeBlock& block = program_.rules[rule].block;
  r.info = &infoOf(block);
  r.regCount = std::uint32_t(block.registerTypes.size());
  r.slotCount = block.slots;
  // A block too large for a chunk stays on runWith, whose enter() reports it.
  if (r.regCount > kRegChunk || r.slotCount > kSlotChunk) return;
  r.regs = rawChunk<Value>(std::max<std::size_t>(r.regCount, 1));
  r.slots = rawChunk<Slot>(std::max<std::size_t>(r.slotCount, 1));
  r.frame = Frame{&block,
                  block.code.data(),
                  r.regs.get(),
                  r.slots.get(),
                  r.info->boxed.data(),
                  r.info->slotFlags.data(),
                  0,
                  false,
                  false,
                  r.info->consumingSlots};
}

void Interpreter::runWith(const CodeBlock& block, const BlockInfo& info, NodeId host, bool negative,
                          PredId triggerPred, const Value* trigger) {
  const Alloc a = enter(block);
  Frame f{
      &block, block.code.data(),  a.regs, a.slots, info.boxed.data(), info.slotFlags.data(), host, negative,
      false,  info.consumingSlots};
  if (trigger) f.slots[0] = Slot{triggerPred, host, kNoFact, 0, trigger};
  try {
    start(f, info.native);
  } catch (...) {
    leave(f, a, info);
    throw;
  }
  leave(f, a, info);
}

Value Interpreter::retained(const Frame& f, std::uint32_t r) const {
  if (f.boxed[r]) heap_.retainObjectValue(f.regs[r]);
  return f.regs[r];
}

void Interpreter::noteDerivation(const Frame& f, std::uint32_t pc, NodeId node, PredId p, const Value* args) {
  const CodeBlock* b = f.block;
  const bool axiom = b == &program_.rules.front().block ||
                     (!program_.axiomBlocks.empty() && b >= &program_.axiomBlocks.front() &&
                      b <= &program_.axiomBlocks.back());
  Derivation d = derivation(axiom, b->label, b->lines, pc, f.host);
  for (std::uint32_t s = 0; s < b->slots; ++s) {
    const Slot& sl = f.slots[s];
    if (sl.fact == kNoFact && !sl.fixed) continue;
    FactAt premise{sl.node, {}};
    appendFact(premise.text, db_, sl.pred, slotArgs(f, s));
    d.premises.push_back(std::move(premise));
  }
  record(std::move(d), node, p, args);
}

Derivation Interpreter::derivation(bool axiom, std::string_view label, std::span<const SourceLine> lines,
                                   std::uint32_t pc, NodeId host) const {
  Derivation d;
  d.kind = axiom ? Derivation::Kind::Axiom : Derivation::Kind::Rule;
  if (const SourceLine* l = lineAt(lines, pc))
    d.where = program_.sourceFiles[l->file] + ":" + std::to_string(l->line);
  d.rule = label.substr(0, label.find('\n'));
  d.at = host;
  if (machine_.derivations_->clock) d.time = machine_.derivations_->clock();
  return d;
}

void Interpreter::record(Derivation d, NodeId node, PredId p, const Value* args) {
  std::string text;
  appendFact(text, db_, p, args);
  machine_.derivations_->record(node, std::move(text), std::move(d));
}

bool Interpreter::boundOutside(const Frame& f, std::uint32_t slot, PredId p, FactRef fact) const {
  for (std::uint32_t s = 0; s < slot; ++s)
    if (f.slots[s].fact == fact && f.slots[s].pred == p && !f.slots[s].fixed) return true;
  return false;
}

inline Interpreter::LoopHead Interpreter::beginLoop(Frame& f, std::uint32_t pc) {
  const std::uint32_t* c = f.code + pc;
  LoopHead h{Opcode(c[0]), c[1], c[2], c[3], pc + 5, 0, Value(), f.host};
  if (h.op == Opcode::ITER_KEY) {
    h.keyField = c[4];
    h.key = f.regs[c[5]];
    h.body = pc + 7;
  } else if (h.op == Opcode::ITER_SORTED) {
    h.keyField = c[4];
    h.body = pc + 6;
  }
  Slot& slot = f.slots[h.slot];
  slot.pred = h.pred;
  // Thread facts (§6.12) live at the running thread's node and are visible to the node's rules.
  if (h.flags & kIterThread) h.at = machine_.threadNode_;
  slot.node = h.at;
  slot.flags = h.flags;
  slot.fixed = nullptr;
  machine_.countStep();  // each loop run: a join that never fires is work too
  return h;
}

// A loop whose body exec runs in place: a plain ITER that fetches no lists ahead, or an ITER_KEY.
// exec steps through it with the helpers below without a call per loop or per fact visited; loop()
// takes the same steps with a call per body (a loop nested too deep, native code's helper).
inline bool Interpreter::runsInPlace(const Frame& f, const std::uint32_t* c) const {
  return Opcode(c[0]) == Opcode::ITER_KEY ||
         (Opcode(c[0]) == Opcode::ITER && !(f.slotFlags[c[2]] & (kSlotWalksLists | kSlotMovesLists)));
}

// Binds the loop's slot and its first fact to visit; false (the loop closed) when there is none.
inline bool Interpreter::openLoop(Frame& f, std::uint32_t pc, OpenLoop& l) {
  const LoopHead h = beginLoop(f, pc);
  l.pred = h.pred;
  l.slot = h.slot;
  l.body = h.body;
  l.after = h.op == Opcode::ITER ? f.code[pc + 4] : f.code[pc + 6];
  l.linear = h.flags & kIterLinear;
  l.returnOnFire = h.flags & kIterReturnOnFire;
  l.fired = false;
  l.tried = 0;
  if (h.op == Opcode::ITER_KEY) {
    // The store's index lists the node's facts with that key in insertion order: the facts a
    // scan with a test would visit, without the others (a join's cost does not grow with the
    // node's number of facts).
    l.index = machine_.keyIndex(h.pred, h.keyField);
    return visitFrom(f, l, db_.firstWithKey(h.at, h.pred, l.index, h.key));
  }
  l.index = OpenLoop::kPlain;
  return visitFrom(f, l, db_.first(h.at, h.pred));
}

// The fact after `fact` in the loop's list, or in its key's chain.
inline FactRef Interpreter::nextInLoop(const OpenLoop& l, FactRef fact) const {
  return l.index == OpenLoop::kPlain ? db_.next(l.pred, fact) : db_.nextWithKey(l.pred, l.index, fact);
}

// Binds the first fact from `fact` on that the loop visits (loop()'s visit); false, the loop
// closed, past the last.
inline bool Interpreter::visitFrom(Frame& f, OpenLoop& l, FactRef fact) {
  for (; fact != kNoFact; fact = nextInLoop(l, fact)) {
    ++l.tried;
    if (l.linear && skipFact(f, l.slot, l.pred, fact)) continue;
    f.slots[l.slot].fact = l.fact = fact;
    return true;
  }
  machine_.stats_.factsTried += l.tried;
  f.slots[l.slot].fact = kNoFact;
  return false;
}

// After a body that ended with `st`: the loop's next fact bound (true), or the loop closed.
inline bool Interpreter::visitNext(Frame& f, OpenLoop& l, Status st) {
  if (st == Status::Fired) l.fired = true;
  if ((st == Status::Fired && l.returnOnFire) || machine_.interrupted()) {
    machine_.stats_.factsTried += l.tried;
    f.slots[l.slot].fact = kNoFact;
    return false;
  }
  return visitFrom(f, l, nextInLoop(l, l.fact));
}

template <class RunBody>
bool Interpreter::loop(Frame& f, std::uint32_t pc, RunBody&& runBody) {
  if (runsInPlace(f, f.code + pc)) {
    OpenLoop l;
    if (!openLoop(f, pc, l)) return false;
    while (visitNext(f, l, runBody(l.body))) {
    }
    return l.fired;
  }
  const LoopHead h = beginLoop(f, pc);
  const auto op = h.op;
  const PredId p = h.pred;
  const std::uint32_t s = h.slot, flags = h.flags, body = h.body, keyField = h.keyField;
  const NodeId at = h.at;
  const bool linear = flags & kIterLinear;
  const bool returnOnFire = flags & kIterReturnOnFire;
  bool fired = false;
  Slot& slot = f.slots[s];

  std::uint64_t tried = 0;                  // added to the statistics once, after the loop
  auto visit = [&](FactRef fact) -> bool {  // false: stop the loop
    ++tried;
    if (linear && skipFact(f, s, p, fact)) return true;
    slot.fact = fact;
    if (runBody(body) == Status::Fired) {
      fired = true;
      if (returnOnFire) return false;
    }
    return !machine_.interrupted();
  };

  if (op != Opcode::ITER_SORTED) {  // a plain ITER that fetches its facts' lists ahead
    // (kSlotMovesLists: only the first cell of each list, fetchDepth 0.)
    const int fetchDepth = f.slotFlags[s] & kSlotWalksLists ? detail::kListFetchAhead - 1 : 0;
    const FactTable& table = db_.table(p);  // (its slot array may move; the table does not)
    const auto listField = std::uint32_t(machine_.tables_.listField[p]);
    const bool pipelined = fetchDepth > 0 && (f.slotFlags[s] & kSlotListsStayPut);
    ListPipeline pipeline;
    for (FactRef fact = db_.first(at, p); fact != kNoFact;) {
      if (pipelined)
        pipeline.step(table, fact, listField);
      else
        walkListsAhead<detail::kListFetchAhead>(table, fact, listField, fetchDepth, nullptr);
      if (!visit(fact)) break;
      fact = db_.next(p, fact);
    }
  } else {
    const std::size_t begin = sorted_.size();
    for (FactRef fact = db_.first(at, p); fact != kNoFact; fact = db_.next(p, fact))
      if (!linear || !db_.consumedMark(p, fact)) sorted_.push_back(fact);
    if (flags & kIterRandom) {
      for (std::size_t i = sorted_.size() - begin; i > 1; --i)
        std::swap(sorted_[begin + i - 1], sorted_[begin + ctx_.rng->next() % i]);
    } else {
      const TypeId t = program_.predicates[p].fields[keyField];
      std::stable_sort(sorted_.begin() + std::ptrdiff_t(begin), sorted_.end(), [&](FactRef a, FactRef b) {
        return compareValuesFast(program_.types, t, db_.args(p, a)[keyField], db_.args(p, b)[keyField]) < 0;
      });
    }
    for (std::size_t i = begin; i < sorted_.size(); ++i)
      if (!visit(sorted_[i])) break;
    sorted_.resize(begin);
  }
  machine_.stats_.factsTried += tried;
  slot.fact = kNoFact;
  return fired;
}

inline void Interpreter::ruleFired() { machine_.stats_.rulesFired++; }

// Runs a block from pc. The bodies of the loops that run in place (runsInPlace) run here, their
// loops on a stack of this call's; the others through loop(), which calls exec for each body.
Interpreter::Status Interpreter::exec(Frame& f, std::uint32_t pc) {
  const std::uint32_t* code = f.code;
  bool lastFired = false;  // the last loop of the current body fired
  Value* R = f.regs;
  OpenLoop open[kOpenLoops];
  std::uint32_t depth = 0;
  Status ended;  // how the current body ended (bodyEnded)
  // Threaded dispatch: a straight-on instruction or a jump ends in its own jump to the next
  // instruction's label through this table (OP_END), where the switch's one shared jump, and the
  // jump back to it, served them all: 2.3-3.1 % fewer instructions on 8queens-12, n-queens 13,
  // heat-transfer and new-heat-transfer (callgrind). Every opcode of opcodes.def needs its label
  // (OP_LABEL) or this does not compile; the switch stays around the cases for step(), which
  // shares them. The loops' cases go back to the loop's top: jumping from them too took 8queens-12
  // 4 % more instructions (GCC 12 allocated the registers worse). The loader verified every
  // instruction (detail::instructionLength): no other opcode reaches here.
  static const void* const kDispatch[] = {
#define OP(name, operands, meaning) &&op_##name,
#include "meldvm/opcodes.def"
#undef OP
  };
#define OP_LABEL(name) op_##name:
#define OP_END   \
  c = code + pc; \
  goto* kDispatch[c[0]]
  for (;;) {
    const std::uint32_t* c = code + pc;
    goto* kDispatch[c[0]];
    switch (Opcode(c[0])) {
      case Opcode::ITER:
        OP_LABEL(ITER);
        [[fallthrough]];
      case Opcode::ITER_KEY:
        OP_LABEL(ITER_KEY);
        if (depth < kOpenLoops && runsInPlace(f, c)) {
          OpenLoop& l = open[depth];
          lastFired = false;
          if (openLoop(f, pc, l)) {
            ++depth;
            pc = l.body;
          } else {
            pc = l.after;
            if (machine_.interrupted()) {
              ended = Status::Return;
              goto bodyEnded;
            }
          }
          break;
        }
        [[fallthrough]];
      case Opcode::ITER_SORTED: {
        OP_LABEL(ITER_SORTED);
        lastFired = loop(f, pc, [&](std::uint32_t body) { return exec(f, body); });
        pc = Opcode(c[0]) == Opcode::ITER ? c[4] : Opcode(c[0]) == Opcode::ITER_KEY ? c[6] : c[5];
        if (machine_.interrupted()) {
          ended = Status::Return;
          goto bodyEnded;
        }
        break;
      }
      case Opcode::NEXT:
        OP_LABEL(NEXT);
        ended = lastFired ? Status::Fired : Status::NotFired;
        goto bodyEnded;
      case Opcode::FIRE:
        OP_LABEL(FIRE);
        fire(f, c[1]);
        ruleFired();
        ended = Status::Fired;
        goto bodyEnded;
      case Opcode::CFIRE:
        OP_LABEL(CFIRE);
        fire(f, c[1]);
        ended = Status::NotFired;
        goto bodyEnded;
      case Opcode::RET:
        OP_LABEL(RET);
        ended = Status::Return;
        goto bodyEnded;
      case Opcode::RET_IF_UPDATED:
        OP_LABEL(RET_IF_UPDATED);
        if (f.updated) {
          ended = Status::Return;
          goto bodyEnded;
        }
        pc += 1;
        OP_END;
      case Opcode::TEST:
        OP_LABEL(TEST);
        pc = testField(f, c) ? pc + 5 : c[4];
        OP_END;
      case Opcode::JF:
        OP_LABEL(JF);
        pc = R[c[1]].asBool() ? pc + 3 : c[2];
        OP_END;
      case Opcode::JT:
        OP_LABEL(JT);
        pc = R[c[1]].asBool() ? c[2] : pc + 3;
        OP_END;
      case Opcode::JMP:
        OP_LABEL(JMP);
        pc = c[1];
        OP_END;
      case Opcode::JNIL:
        OP_LABEL(JNIL);
        pc = R[c[1]].isNil() ? c[2] : pc + 3;
        OP_END;
      case Opcode::JNOTNIL:
        OP_LABEL(JNOTNIL);
        pc = R[c[1]].isNil() ? pc + 3 : c[2];
        OP_END;
#include "straight_ops.inc"
      default:
        __builtin_unreachable();
    }
    continue;  // (the loops' cases, which break)
#undef OP_LABEL
#undef OP_END
  bodyEnded:
    // The body of the innermost open loop ended (the loop goes on or closes), or the block did.
    for (;;) {
      if (depth == 0) return ended;
      OpenLoop& l = open[depth - 1];
      if (visitNext(f, l, ended)) {
        lastFired = false;
        pc = l.body;
        break;
      }
      --depth;
      lastFired = l.fired;
      pc = l.after;
      if (!machine_.interrupted()) break;
      ended = Status::Return;  // as loop()'s caller: the enclosing body ends too
    }
  }
}

template <Opcode OP>
void Interpreter::step(Frame& f, std::uint32_t pc) {
  [[maybe_unused]] const std::uint32_t* c = f.code + pc;
  [[maybe_unused]] Value* R = f.regs;
#define OP_LABEL(name)
#define OP_END break
  switch (OP) {  // a constant: only OP's case is compiled in
#include "straight_ops.inc"
#undef OP_LABEL
#undef OP_END
    default:
      throw RuntimeError(std::string("opcode ") + opcodeInfo(OP).name + " has no native step");
  }
}

// ---- the helpers of native code (native_abi.h): the interpreter's code for each instruction ----

struct NativeHelpers {
  using Slot = Interpreter::Slot;  // native code reads and binds the frame's slots in place
  static_assert(sizeof(Slot) == sizeof(meld_native_slot) &&
                offsetof(Slot, pred) == offsetof(meld_native_slot, pred) &&
                offsetof(Slot, node) == offsetof(meld_native_slot, node) &&
                offsetof(Slot, fact) == offsetof(meld_native_slot, fact) &&
                offsetof(Slot, flags) == offsetof(meld_native_slot, flags) &&
                offsetof(Slot, fixed) == offsetof(meld_native_slot, fixed) && kNoFact == MELD_NATIVE_NO_FACT);
  // A cell is its header, its head, then its tail (offsetof is not defined on a derived struct).
  static_assert(sizeof(Object) == 8 * MELD_NATIVE_LIST_HEAD_WORD &&
                sizeof(Object) + sizeof(Value) == 8 * MELD_NATIVE_LIST_TAIL_WORD &&
                sizeof(ConsCell) == 8 * (MELD_NATIVE_LIST_TAIL_WORD + 1));
  // Native CONS writes the header as two 32-bit words: the count, then the type (meld_native_heap).
  static_assert(offsetof(Object, refs) == 0 && offsetof(Object, type) == 4 && sizeof(TypeId) == 4);
  static_assert(sizeof(bool) == 1 && sizeof(std::atomic<bool>) == 1 && std::atomic<bool>::is_always_lock_free,
                "native code reads the stop flags as bytes");
  static Interpreter& vm(meld_native_vm* v) {
    return *static_cast<Interpreter*>(reinterpret_cast<meld_native_context*>(v)->interpreter);
  }
  static Interpreter::Frame& frame(meld_native_frame* f) { return *reinterpret_cast<Interpreter::Frame*>(f); }

  // ITER and ITER_KEY loops run in native code: the slot is bound here, native code steps through
  // the facts (the same order, skips and statistics as loop()).
  static void loopBegin(meld_native_vm* v, meld_native_frame* fr, std::uint32_t pc, meld_native_loop* out) {
    Interpreter& in = vm(v);
    Interpreter::Frame& f = frame(fr);
    const Interpreter::LoopHead h = in.beginLoop(f, pc);
    // The same fields as native code's own beginLoop, from the same context.
    const meld_native_context& c = in.nativeContext_;
    const meld_native_table& table = c.tables[h.pred];
    out->slots = reinterpret_cast<meld_native_slot*>(f.slots);
    out->words = table.words;
    out->stop = c.stop;
    out->shared_stop = c.shared_stop;
    out->stride = table.stride;
    out->arg_offset = table.arg_offset;
    if (h.op == Opcode::ITER_KEY) {
      const std::uint32_t ix = in.machine_.keyIndex(h.pred, h.keyField);
      out->first = in.db_.firstWithKey(h.at, h.pred, ix, h.key);
      out->next_word = in.db_.table(h.pred).indexLinkWord(ix);
    } else {
      out->first = in.db_.first(h.at, h.pred);
      out->next_word = 0;
    }
  }
  static int32_t loop(const meld_native_helpers* h, meld_native_vm* v, meld_native_frame* fr,
                      std::uint32_t pc, meld_native_block body) {
    Interpreter& in = vm(v);
    Interpreter::Frame& f = frame(fr);
    const bool fired = in.loop(f, pc, [&](std::uint32_t) {
      return Interpreter::Status(body(h, v, fr, reinterpret_cast<std::uint64_t*>(f.regs)));
    });
    if (in.machine_.interrupted()) return int32_t(Interpreter::Status::Return);
    return int32_t(fired ? Interpreter::Status::Fired : Interpreter::Status::NotFired);
  }
  template <Opcode OP>
  static void step(meld_native_vm* v, meld_native_frame* f, std::uint32_t pc) {
    vm(v).step<OP>(frame(f), pc);
  }
  static int32_t test(meld_native_vm* v, meld_native_frame* fr, std::uint32_t pc) {
    const Interpreter::Frame& f = frame(fr);
    return vm(v).testField(f, f.code + pc);
  }
  static void consume(meld_native_vm* v, meld_native_frame* fr, std::uint32_t s) {
    Interpreter& in = vm(v);
    const Slot& sl = frame(fr).slots[s];
    if (in.consumable(sl)) in.consumeSlot(sl);
  }
  static int32_t updated(meld_native_frame* f) { return frame(f).updated; }
  static void derive(meld_native_vm* v, meld_native_frame* f, std::uint32_t pc, std::uint32_t pred,
                     const std::uint64_t* args) {
    vm(v).deriveFact(frame(f), pc, pred, reinterpret_cast<const Value*>(args));
  }
  static void send(meld_native_vm* v, meld_native_frame* f, std::uint32_t pc, std::uint32_t pred,
                   std::uint32_t dest, const std::uint64_t* args) {
    vm(v).sendFact(frame(f), pc, pred, dest, reinterpret_cast<const Value*>(args), 0);
  }
  static void update(meld_native_vm* v, meld_native_frame* f, std::uint32_t pc, std::uint32_t slot,
                     std::uint32_t moveToBack, const std::uint64_t* args) {
    vm(v).updateFact(frame(f), pc, slot, moveToBack != 0, reinterpret_cast<const Value*>(args));
  }
  static const std::uint64_t* slotArgs(meld_native_vm* v, meld_native_frame* f, std::uint32_t slot) {
    static_assert(sizeof(Value) == sizeof(std::uint64_t));
    return reinterpret_cast<const std::uint64_t*>(vm(v).slotArgs(frame(f), slot));
  }
  static void releaseLast(meld_native_vm* v, std::uint32_t type, std::uint64_t value) {
    vm(v).heap_.release(TypeId(type), Value::fromBits(value));
  }

  template <BuiltinFn F>
  static std::uint64_t builtin(meld_native_vm* v, const std::uint64_t* args, std::uint32_t count,
                               std::uint32_t result) {
    return F(vm(v).ctx_, {reinterpret_cast<const Value*>(args), count}, TypeId(result)).bits();
  }
  static constexpr meld_native_builtin kBuiltins[] = {
      // builtins.def's ids are dense, in order
#define BUILTIN(id, name, impl, signature, typeArg) &builtin<&builtins::impl>,
#include "meldvm/builtins.def"
#undef BUILTIN
  };
  static_assert(std::size(kBuiltins) == kBuiltinIdCount);

  static constexpr meld_native_step kSteps[] = {
#define OP(name, operands, meaning) &step<Opcode::name>,
#include "meldvm/opcodes.def"
#undef OP
  };
  static constexpr meld_native_helpers kTable = {
      MELD_NATIVE_ABI_VERSION,
      &loop,
      kSteps,
      &test,
      &consume,
      &updated,
      &slotArgs,
      &releaseLast,
      &loopBegin,
      kBuiltins,
      &derive,
      &send,
      &update,
  };
};

const meld_native_helpers* Interpreter::helperTable() { return &NativeHelpers::kTable; }

Interpreter::Status Interpreter::start(Frame& f, meld_native_block native) {
  if (!native) return exec(f, 0);
  return Status(native(nativeHelpers_, reinterpret_cast<meld_native_vm*>(&nativeContext_),
                       reinterpret_cast<meld_native_frame*>(&f), reinterpret_cast<std::uint64_t*>(f.regs)));
}

Value Interpreter::callFunction(std::uint32_t fn, const Value* args, NodeId host) {
  const Function& func = program_.functions[fn];
  const char probe = 0;
  if (depth_ == 0) stackTop_ = &probe;
  const auto used = std::intptr_t(reinterpret_cast<std::uintptr_t>(stackTop_)) -
                    std::intptr_t(reinterpret_cast<std::uintptr_t>(&probe));  // the stack grows down
  if (used > kMaxCallStackBytes)
    throw RuntimeError("function '" + func.name + "' nested " + std::to_string(depth_) +
                       " calls deep: more stack than 6 MiB (runaway recursion?)");
  ++depth_;
  const Alloc a = enter(func.block);
  const BlockInfo& info = infoOf(func.block);
  Frame f{&func.block,
          func.block.code.data(),
          a.regs,
          a.slots,
          info.boxed.data(),
          info.slotFlags.data(),
          host,
          false,
          false,
          info.consumingSlots};
  const std::size_t n = func.params.size();
  for (std::size_t i = 0; i < n; ++i) {
    heap_.retain(func.params[i], args[i]);
    f.regs[i] = args[i];
  }
  try {
    start(f, info.native);
  } catch (...) {
    leave(f, a, info);
    --depth_;
    throw;
  }
  const Value result = f.regs[n];
  f.regs[n] = Value();  // ownership moves to the caller
  leave(f, a, info);
  --depth_;
  return result;
}

}  // namespace meldvm
