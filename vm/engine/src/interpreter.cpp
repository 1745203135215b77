#include "interpreter.hpp"

#include <algorithm>
#include <cstring>

#include "meldvm/arith.hpp"
#include "meldvm/bytecode_internal.hpp"
#include "meldvm/derivation_log.hpp"
#include "meldvm/dump.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/value_ops.hpp"

namespace meldvm {

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

Interpreter::Interpreter(Machine& machine, const Program& program, Database& db, BuiltinContext& ctx)
    : machine_(machine), program_(program), db_(db), heap_(db.heap()), ctx_(ctx) {
  regChunks_.push_back(std::make_unique<Value[]>(kRegChunk));
  slotChunks_.push_back(std::make_unique<Slot[]>(kSlotChunk));
  args_.resize(64);
}

Interpreter::~Interpreter() = default;

// Per register whether it is boxed, then whether any register is (leave() skips the release loop
// otherwise), then whether any loop consumes its fact (fire() has nothing to do otherwise).
void Interpreter::blockFlags(const CodeBlock& b, std::vector<std::uint8_t>& v, bool scanLoops) const {
  const std::size_t regs = b.registerTypes.size();
  v.assign(regs + 2, 0);
  for (std::size_t r = 0; r < regs; ++r) {
    v[r] = program_.types.boxed(b.registerTypes[r]);
    v[regs] |= v[r];
  }
  if (scanLoops)
    detail::forEachInstruction(b.code, [&](std::size_t pc) {
      if (detail::isLoop(b.code[pc]) && (b.code[pc + 3] & kIterConsume)) v[regs + 1] = 1;
    });
}

const std::vector<std::uint8_t>& Interpreter::boxedOf(const CodeBlock& b) {
  if (&b == lastBlock_) return *lastBoxed_;
  const auto& axioms = program_.axiomBlocks;
  if (!axioms.empty() && &b >= axioms.data() && &b < axioms.data() + axioms.size()) {
    // An axiom block runs once: no cache entry (a big program has millions of them). Axiom
    // blocks are straight-line code (no loops) and never nest, so one scratch serves them all.
    blockFlags(b, axiomBoxed_, false);
    return axiomBoxed_;
  }
  auto it = boxed_.find(&b);
  if (it == boxed_.end()) {
    std::vector<std::uint8_t> v;
    blockFlags(b, v, true);
    it = boxed_.emplace(&b, std::move(v)).first;
  }
  lastBlock_ = &b;
  lastBoxed_ = &it->second;
  return it->second;
}

Interpreter::Alloc Interpreter::enter(const CodeBlock& b) {
  const std::size_t regs = b.registerTypes.size(), slots = b.slots;
  if (regs > kRegChunk || slots > kSlotChunk) throw RuntimeError("code block '" + b.label + "' is too large");
  Alloc a{nullptr, nullptr, regChunk_ * kRegChunk + regUsed_, slotChunk_ * kSlotChunk + slotUsed_};
  if (regUsed_ + regs > kRegChunk) {
    if (++regChunk_ == regChunks_.size()) regChunks_.push_back(std::make_unique<Value[]>(kRegChunk));
    regUsed_ = 0;
  }
  if (slotUsed_ + slots > kSlotChunk) {
    if (++slotChunk_ == slotChunks_.size()) slotChunks_.push_back(std::make_unique<Slot[]>(kSlotChunk));
    slotUsed_ = 0;
  }
  a.regs = regChunks_[regChunk_].get() + regUsed_;
  a.slots = slotChunks_[slotChunk_].get() + slotUsed_;
  regUsed_ += regs;
  slotUsed_ += slots;
  std::fill(a.regs, a.regs + regs, Value());
  for (std::size_t s = 0; s < slots; ++s) a.slots[s] = Slot{0, 0, kNoFact, 0, nullptr};
  return a;
}

void Interpreter::leave(const Frame& f, const Alloc& a) {
  const std::size_t regs = f.block->registerTypes.size();
  if (f.boxed[regs])
    for (std::size_t r = 0; r < regs; ++r)
      if (f.boxed[r]) heap_.release(f.block->registerTypes[r], f.regs[r]);
  regChunk_ = a.regMark / kRegChunk;
  regUsed_ = a.regMark % kRegChunk;
  slotChunk_ = a.slotMark / kSlotChunk;
  slotUsed_ = a.slotMark % kSlotChunk;
}

void Interpreter::run(const CodeBlock& block, NodeId host, bool negative, PredId triggerPred,
                      const Value* trigger) {
  const Alloc a = enter(block);
  Frame f{&block, block.code.data(), a.regs, a.slots, boxedOf(block).data(), host, negative};
  if (trigger) f.slots[0] = Slot{triggerPred, host, kNoFact, 0, trigger};
  try {
    exec(f, 0);
  } catch (...) {
    leave(f, a);
    throw;
  }
  leave(f, a);
}

Value Interpreter::retained(const Frame& f, std::uint32_t r) const {
  heap_.retain(f.block->registerTypes[r], f.regs[r]);
  return f.regs[r];
}

void Interpreter::consumeSlot(const Slot& sl) { machine_.consumed(sl.node, sl.pred, sl.fact); }

void Interpreter::noteDerivation(const Frame& f, std::uint32_t pc, NodeId node, PredId p, const Value* args) {
  Derivation d;
  const CodeBlock* b = f.block;
  const bool axiom = b == &program_.rules.front().block ||
                     (!program_.axiomBlocks.empty() && b >= &program_.axiomBlocks.front() &&
                      b <= &program_.axiomBlocks.back());
  d.kind = axiom ? Derivation::Kind::Axiom : Derivation::Kind::Rule;
  if (const SourceLine* l = b->lineAt(pc))
    d.where = program_.sourceFiles[l->file] + ":" + std::to_string(l->line);
  d.rule = b->label.substr(0, b->label.find('\n'));
  d.at = f.host;
  DerivationLog& log = *machine_.derivations_;
  if (log.clock) d.time = log.clock();
  for (std::uint32_t s = 0; s < b->slots; ++s) {
    const Slot& sl = f.slots[s];
    if (sl.fact == kNoFact && !sl.fixed) continue;
    FactAt premise{sl.node, {}};
    appendFact(premise.text, db_, sl.pred, slotArgs(f, s));
    d.premises.push_back(std::move(premise));
  }
  std::string text;
  appendFact(text, db_, p, args);
  log.record(node, std::move(text), std::move(d));
}

bool Interpreter::skipFact(const Frame& f, std::uint32_t slot, PredId p, FactRef fact) const {
  if (db_.consumedMark(p, fact)) return true;
  for (std::uint32_t s = 0; s < slot; ++s)  // §6.4.3: a fact bound by an enclosing loop
    if (f.slots[s].fact == fact && f.slots[s].pred == p && !f.slots[s].fixed) return true;
  return false;
}

bool Interpreter::loop(Frame& f, std::uint32_t pc) {
  const std::uint32_t* c = f.code + pc;
  const auto op = Opcode(c[0]);
  const PredId p = c[1];
  const std::uint32_t s = c[2], flags = c[3];
  std::uint32_t body;
  std::uint32_t keyField = 0;
  Value key;
  if (op == Opcode::ITER) {
    body = pc + 5;
  } else if (op == Opcode::ITER_KEY) {
    keyField = c[4];
    key = f.regs[c[5]];
    body = pc + 7;
  } else {
    keyField = c[4];
    body = pc + 6;
  }
  const bool linear = flags & kIterLinear;
  const bool returnOnFire = flags & kIterReturnOnFire;
  bool fired = false;
  Slot& slot = f.slots[s];
  slot.pred = p;
  // Thread facts (§6.12) live at the running thread's node and are visible to the node's rules.
  const NodeId at = (flags & kIterThread) ? machine_.threadNode_ : f.host;
  slot.node = at;
  slot.flags = flags;
  slot.fixed = nullptr;

  machine_.countStep();                     // each loop run: a join that never fires is work too
  std::uint64_t tried = 0;                  // added to the statistics once, after the loop
  auto visit = [&](FactRef fact) -> bool {  // false: stop the loop
    ++tried;
    if (linear && skipFact(f, s, p, fact)) return true;
    slot.fact = fact;
    if (exec(f, body) == Status::Fired) {
      fired = true;
      if (returnOnFire) return false;
    }
    return !machine_.stopRequested();
  };

  if (op == Opcode::ITER_KEY) {
    // The store's index lists the node's facts with that key in insertion order: the facts a
    // scan with a test would visit, without the others (a join's cost does not grow with the
    // node's number of facts).
    const std::uint32_t ix = machine_.keyIndex(p, keyField);
    for (FactRef fact = db_.firstWithKey(at, p, ix, key); fact != kNoFact;) {
      if (!visit(fact)) break;
      fact = db_.nextWithKey(p, ix, fact);
    }
  } else if (op != Opcode::ITER_SORTED) {
    for (FactRef fact = db_.first(at, p); fact != kNoFact;) {
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

Interpreter::Status Interpreter::exec(Frame& f, std::uint32_t pc) {
  const std::uint32_t* code = f.code;
  bool lastFired = false;
  Value* R = f.regs;
  for (;;) {
    const std::uint32_t* c = code + pc;
    switch (Opcode(c[0])) {
      case Opcode::ITER:
      case Opcode::ITER_KEY:
      case Opcode::ITER_SORTED: {
        lastFired = loop(f, pc);
        pc = Opcode(c[0]) == Opcode::ITER ? c[4] : Opcode(c[0]) == Opcode::ITER_KEY ? c[6] : c[5];
        if (machine_.stopRequested()) return Status::Return;
        break;
      }
      case Opcode::NEXT:
        return lastFired ? Status::Fired : Status::NotFired;
      case Opcode::FIRE:
        fire(f, c[1]);
        machine_.stats_.rulesFired++;
        return Status::Fired;
      case Opcode::CFIRE:
        fire(f, c[1]);
        return Status::NotFired;
      case Opcode::RET:
        return Status::Return;
      case Opcode::RET_IF_UPDATED:
        if (f.updated) return Status::Return;
        pc += 1;
        break;
      case Opcode::LOAD: {
        const Value v = slotArgs(f, c[1])[c[2]];
        if (f.boxed[c[3]]) {
          heap_.retain(f.block->registerTypes[c[3]], v);
          setReg(f, c[3], v);
        } else {
          R[c[3]] = v;
        }
        pc += 4;
        break;
      }
      case Opcode::TEST: {
        const Slot& sl = f.slots[c[1]];
        const TypeId t = program_.predicates[sl.pred].fields[c[2]];
        pc = valuesEqualFast(program_.types, t, slotArgs(f, c[1])[c[2]], R[c[3]]) ? pc + 5 : c[4];
        break;
      }
      case Opcode::JF:
        pc = R[c[1]].asBool() ? pc + 3 : c[2];
        break;
      case Opcode::JT:
        pc = R[c[1]].asBool() ? c[2] : pc + 3;
        break;
      case Opcode::JMP:
        pc = c[1];
        break;
      case Opcode::JNIL:
        pc = R[c[1]].isNil() ? c[2] : pc + 3;
        break;
      case Opcode::JNOTNIL:
        pc = R[c[1]].isNil() ? pc + 3 : c[2];
        break;
      case Opcode::MOV:
        setReg(f, c[1], retained(f, c[2]));
        pc += 3;
        break;
      case Opcode::MOVI:
        R[c[1]] = Value::fromInt(std::int32_t(c[2]));
        pc += 3;
        break;
      case Opcode::MOVF:
        R[c[1]] = Value::fromFloat(immDouble(c + 2));
        pc += 4;
        break;
      case Opcode::MOVB:
        R[c[1]] = Value::fromBool(c[2] != 0);
        pc += 3;
        break;
      case Opcode::MOVN:
        R[c[1]] = Value::fromNode(c[2]);
        pc += 3;
        break;
      case Opcode::MOVS: {
        const Value v = machine_.strings_[c[2]];
        heap_.retain(TypeTable::kString, v);
        setReg(f, c[1], v);
        pc += 3;
        break;
      }
      case Opcode::NIL:
        setReg(f, c[1], Value::nil());
        pc += 2;
        break;
      case Opcode::GLOBAL: {
        const Value v = machine_.globals_[c[2]];
        heap_.retain(f.block->registerTypes[c[1]], v);
        setReg(f, c[1], v);
        pc += 3;
        break;
      }
      case Opcode::SETGLOBAL: {
        Value& g = machine_.globals_[c[1]];
        const TypeId t = program_.globals[c[1]].type;
        heap_.release(t, g);
        g = retained(f, c[2]);
        pc += 3;
        break;
      }
      case Opcode::HOST:
        R[c[1]] = Value::fromNode(f.host);
        pc += 2;
        break;
      case Opcode::WORLD:
        R[c[1]] = Value::fromInt(std::int32_t(db_.nodeCount()));
        pc += 2;
        break;
      case Opcode::CPUS:
        R[c[1]] = Value::fromInt(std::int32_t(machine_.placement_.threads));
        pc += 2;
        break;
      case Opcode::THREAD:
        R[c[1]] = Value::fromThread(machine_.placement_.self);
        pc += 2;
        break;
      case Opcode::ARG:
        setReg(f, c[1], machine_.programArg(c[2]));
        pc += 3;
        break;
      case Opcode::ADDI:
        R[c[1]] = Value::fromInt(intAdd(R[c[2]].asInt(), R[c[3]].asInt()));
        pc += 4;
        break;
      case Opcode::SUBI:
        R[c[1]] = Value::fromInt(intSub(R[c[2]].asInt(), R[c[3]].asInt()));
        pc += 4;
        break;
      case Opcode::MULI:
        R[c[1]] = Value::fromInt(intMul(R[c[2]].asInt(), R[c[3]].asInt()));
        pc += 4;
        break;
      case Opcode::DIVI:
        R[c[1]] = Value::fromInt(intDiv(R[c[2]].asInt(), R[c[3]].asInt()));
        pc += 4;
        break;
      case Opcode::MODI:
        R[c[1]] = Value::fromInt(intMod(R[c[2]].asInt(), R[c[3]].asInt()));
        pc += 4;
        break;
      case Opcode::ADDF:
        R[c[1]] = Value::fromFloat(R[c[2]].asFloat() + R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::SUBF:
        R[c[1]] = Value::fromFloat(R[c[2]].asFloat() - R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::MULF:
        R[c[1]] = Value::fromFloat(R[c[2]].asFloat() * R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::DIVF:
        R[c[1]] = Value::fromFloat(R[c[2]].asFloat() / R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::MINI:
        R[c[1]] = Value::fromInt(std::min(R[c[2]].asInt(), R[c[3]].asInt()));
        pc += 4;
        break;
      case Opcode::I2F:
        R[c[1]] = Value::fromFloat(intToFloat(R[c[2]].asInt()));
        pc += 3;
        break;
      case Opcode::EQ:
        R[c[1]] = Value::fromBool(valuesEqualFast(program_.types, c[4], R[c[2]], R[c[3]]));
        pc += 5;
        break;
      case Opcode::NE:
        R[c[1]] = Value::fromBool(!valuesEqualFast(program_.types, c[4], R[c[2]], R[c[3]]));
        pc += 5;
        break;
      case Opcode::LTI:
        R[c[1]] = Value::fromBool(R[c[2]].asInt() < R[c[3]].asInt());
        pc += 4;
        break;
      case Opcode::LEI:
        R[c[1]] = Value::fromBool(R[c[2]].asInt() <= R[c[3]].asInt());
        pc += 4;
        break;
      case Opcode::GTI:
        R[c[1]] = Value::fromBool(R[c[2]].asInt() > R[c[3]].asInt());
        pc += 4;
        break;
      case Opcode::GEI:
        R[c[1]] = Value::fromBool(R[c[2]].asInt() >= R[c[3]].asInt());
        pc += 4;
        break;
      case Opcode::LTF:
        R[c[1]] = Value::fromBool(R[c[2]].asFloat() < R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::LEF:
        R[c[1]] = Value::fromBool(R[c[2]].asFloat() <= R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::GTF:
        R[c[1]] = Value::fromBool(R[c[2]].asFloat() > R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::GEF:
        R[c[1]] = Value::fromBool(R[c[2]].asFloat() >= R[c[3]].asFloat());
        pc += 4;
        break;
      case Opcode::NOT:
        R[c[1]] = Value::fromBool(!R[c[2]].asBool());
        pc += 3;
        break;
      case Opcode::CONS:
        setReg(f, c[1], heap_.cons(c[4], R[c[2]], R[c[3]]));
        pc += 5;
        break;
      case Opcode::HEAD: {
        if (R[c[2]].isNil()) throw RuntimeError("head of an empty list");
        const Value v = listHead(R[c[2]]);
        heap_.retain(f.block->registerTypes[c[1]], v);
        setReg(f, c[1], v);
        pc += 3;
        break;
      }
      case Opcode::TAIL: {
        if (R[c[2]].isNil()) throw RuntimeError("tail of an empty list");
        const Value v = listTail(R[c[2]]);
        heap_.retain(f.block->registerTypes[c[1]], v);
        setReg(f, c[1], v);
        pc += 3;
        break;
      }
      case Opcode::STRUCT: {
        setReg(f, c[1], heap_.makeTuple(c[2], gatherArgs(f, c + 4, c[3])));
        pc += 4 + c[3];
        break;
      }
      case Opcode::FIELD: {
        const Value v = tupleItems(R[c[2]])[c[3]];
        heap_.retain(f.block->registerTypes[c[1]], v);
        setReg(f, c[1], v);
        pc += 4;
        break;
      }
      case Opcode::CALL: {
        const BuiltinFn fn = builtinFunction(std::uint16_t(c[2]));  // the verifier checked the id
        setReg(f, c[1], fn(ctx_, gatherArgs(f, c + 5, c[4]), c[3]));
        pc += 5 + c[4];
        break;
      }
      case Opcode::CALLF: {
        gatherArgs(f, c + 4, c[3]);
        setReg(f, c[1], callFunction(c[2], args_.data(), f.host));
        pc += 4 + c[3];
        break;
      }
      case Opcode::CALLX:
        throw RuntimeError("extern function '" + program_.externs[c[2]].name +
                           "' is not available: this VM links no external code");
      case Opcode::DERIVE:
        gatherArgs(f, c + 3, c[2]);
        if (machine_.derivations_ && !f.negative) [[unlikely]]
          noteDerivation(f, pc, f.host, c[1], args_.data());
        machine_.derive(f.host, c[1], args_.data(), f.negative);
        pc += 3 + c[2];
        break;
      case Opcode::SEND:
        gatherArgs(f, c + 4, c[3]);
        if (machine_.derivations_ && !f.negative) [[unlikely]]
          noteDerivation(f, pc, R[c[2]].asNode(), c[1], args_.data());
        machine_.send(f.host, R[c[2]].asNode(), c[1], args_.data(), f.negative);
        pc += 4 + c[3];
        break;
      case Opcode::SEND_THREAD:
        gatherArgs(f, c + 4, c[3]);
        machine_.sendThread(f.host, R[c[2]].asThread(), c[1], args_.data(), f.negative);
        pc += 4 + c[3];
        break;
      case Opcode::SEND_DELAY:
        gatherArgs(f, c + 5, c[4]);
        if (machine_.derivations_ && !f.negative) [[unlikely]]
          noteDerivation(f, pc, R[c[2]].asNode(), c[1], args_.data());
        machine_.send(f.host, R[c[2]].asNode(), c[1], args_.data(), f.negative, c[3]);
        pc += 5 + c[4];
        break;
      case Opcode::UPDATE: {
        gatherArgs(f, c + 4, c[3]);
        const Slot& sl = f.slots[c[1]];
        if (machine_.derivations_ && !f.negative) [[unlikely]]
          noteDerivation(f, pc, sl.node, sl.pred, args_.data());
        if (!f.negative) machine_.updated(sl.node, sl.pred, sl.fact, args_.data(), c[2] & kUpdateMoveToBack);
        f.updated = true;
        pc += 4 + c[3];
        break;
      }
      case Opcode::ACTION:
        gatherArgs(f, c + 4, c[3]);
        if (!f.negative) machine_.action(f.host, R[c[2]].asNode(), c[1], args_.data());
        pc += 4 + c[3];
        break;
      case Opcode::AXIOMS: {
        const std::uint32_t idx =
            f.host < program_.nodeAxioms.size() ? program_.nodeAxioms[f.host] : Program::kNoAxioms;
        if (idx != Program::kNoAxioms) {
          run(program_.axiomBlocks[idx], f.host);
        }
        pc += 1;
        break;
      }
      case Opcode::NEWNODE:
        R[c[1]] = Value::fromNode(machine_.newNode());
        pc += 2;
        break;
      case Opcode::SET_PRIORITY:
        if (!f.negative) machine_.priorityRequest(R[c[1]].asNode(), R[c[2]].asFloat());
        pc += 3;
        break;
      case Opcode::ADD_PRIORITY:
      case Opcode::SET_DEFAULT_PRIORITY:
        if (!f.negative) machine_.coordination(Opcode(c[0]), R[c[1]].asNode(), R[c[2]]);
        pc += 3;
        break;
      case Opcode::SET_CPU:
      case Opcode::SET_AFFINITY:
        if (!f.negative) machine_.coordination(Opcode(c[0]), R[c[1]].asNode(), R[c[2]]);
        pc += 3;
        break;
      case Opcode::REMOVE_PRIORITY:
      case Opcode::SCHEDULE_NEXT:
      case Opcode::SET_STATIC:
      case Opcode::SET_MOVING:
        if (!f.negative) machine_.coordination(Opcode(c[0]), R[c[1]].asNode(), Value());
        pc += 2;
        break;
      case Opcode::STOP_PROGRAM:
        if (!f.negative) machine_.stopProgram();
        pc += 2;
        break;
      default:
        throw RuntimeError("bad opcode " + std::to_string(c[0]));
    }
  }
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
  Frame f{&func.block, func.block.code.data(), a.regs, a.slots, boxedOf(func.block).data(), host, false};
  const std::size_t n = func.params.size();
  for (std::size_t i = 0; i < n; ++i) {
    heap_.retain(func.params[i], args[i]);
    f.regs[i] = args[i];
  }
  try {
    exec(f, 0);
  } catch (...) {
    leave(f, a);
    --depth_;
    throw;
  }
  const Value result = f.regs[n];
  f.regs[n] = Value();  // ownership moves to the caller
  leave(f, a);
  --depth_;
  return result;
}

}  // namespace meldvm
