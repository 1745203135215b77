// Bytecode to LLVM IR, one lowering per opcode (the switch in lowerInstruction lists every opcode of
// opcodes.def: -Wswitch says when one is missing).
//
// A code block becomes one function per place the interpreter's exec() is entered: the block's
// start, and the body of each of its loops (the loop helper calls it once per fact it binds). Each
// function returns what exec() returns there (native_abi.h). Inside a function every instruction
// is a basic block; jumps are branches, arithmetic on unboxed registers is inlined, and the other
// instructions call the VM's helper that runs the interpreter's own code for them.
#include "lower_block.hpp"

#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Module.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <set>
#include <string>

#include "meldvm/builtin_signatures.hpp"
#include "meldvm/bytecode_internal.hpp"

namespace meldc::native {

using meldvm::Opcode;

namespace {

// Fields of meld_native_helpers (native_abi.h), in order.
enum Helper : unsigned {
  kAbiVersion,
  kLoop,
  kSteps,
  kTest,
  kConsume,
  kUpdated,
  kSlotArgs,
  kRuleFired,
  kReleaseLast,
  kLoopBegin,
  kLoopEnd,
  kBuiltins
};
// Fields of meld_native_loop and meld_native_slot, in order.
enum LoopField : unsigned {
  kLoopSlots,
  kLoopWords,
  kLoopStop,
  kLoopSharedStop,
  kLoopFirst,
  kLoopStride,
  kLoopNextWord,
  kLoopArgOffset
};
enum SlotField : unsigned { kSlotPred, kSlotNode, kSlotFact, kSlotFlags, kSlotFixed };
enum Status : std::int32_t { kNotFired = 0, kFired = 1, kReturn = 2 };
// The LLVM struct of the helpers ({i32, ptr, ...}) puts field k at 8 * k: so must the C one.
static_assert(offsetof(meld_native_helpers, loop) == kLoop * 8 &&
              offsetof(meld_native_helpers, steps) == kSteps * 8 &&
              offsetof(meld_native_helpers, test) == kTest * 8 &&
              offsetof(meld_native_helpers, consume) == kConsume * 8 &&
              offsetof(meld_native_helpers, updated) == kUpdated * 8 &&
              offsetof(meld_native_helpers, slot_args) == kSlotArgs * 8 &&
              offsetof(meld_native_helpers, rule_fired) == kRuleFired * 8 &&
              offsetof(meld_native_helpers, release_last) == kReleaseLast * 8 &&
              offsetof(meld_native_helpers, loop_begin) == kLoopBegin * 8 &&
              offsetof(meld_native_helpers, loop_end) == kLoopEnd * 8 &&
              offsetof(meld_native_helpers, builtins) == kBuiltins * 8 &&
              sizeof(meld_native_helpers) == (kBuiltins + 1) * 8);
static_assert(offsetof(meld_native_loop, words) == 8 * kLoopWords && offsetof(meld_native_loop, stop) == 8 * kLoopStop &&
              offsetof(meld_native_loop, shared_stop) == 8 * kLoopSharedStop &&
              offsetof(meld_native_loop, first) == 8 * kLoopFirst &&
              offsetof(meld_native_loop, stride) == 8 * kLoopFirst + 4 &&
              offsetof(meld_native_loop, next_word) == 8 * kLoopFirst + 8 &&
              offsetof(meld_native_loop, arg_offset) == 8 * kLoopFirst + 12 && sizeof(meld_native_loop) == 48);
static_assert(offsetof(meld_native_slot, fact) == 4 * kSlotFact && offsetof(meld_native_slot, fixed) == 16 &&
              sizeof(meld_native_slot) == 24);

class RegionLowering {
 public:
  RegionLowering(NativeTypes& t, const meldvm::Program& program, const meldvm::CodeBlock& block,
                 std::string prefix, bool process)
      : t_(t), program_(program), block_(block), code_(block.code), prefix_(std::move(prefix)) {
    // Which loop slots consume the fact they bind (FIRE has nothing to consume past the last).
    meldvm::detail::forEachInstruction(code_, [&](std::size_t pc) {
      if (!meldvm::detail::isLoop(code_[pc])) return;
      const std::uint32_t pred = code_[pc + 1], slot = code_[pc + 2];
      if (code_[pc + 3] & meldvm::kIterConsume) {
        consumingSlots_.insert(slot);
      }
      const auto [it, fresh] = slotPreds_.try_emplace(slot, pred);
      if (!fresh && it->second != pred) it->second = -1;
    });
    // A persistent process's slot 0 holds the fact that triggered it (any predicate it names).
    if (process) slotPreds_.erase(0);
  }

  // The function for the code entered at `start` (created on first request, lowered at once).
  // The block's start and the bodies of ITER_SORTED loops (run by the VM's loop helper) are
  // meld_native_block functions; a body that native code loops over also gets the loops array
  // (what loop_begin said about each loop slot bound natively: `bound` lists them).
  llvm::Function* region(std::uint32_t start, const std::set<std::uint32_t>& bound = {}, bool nativeBody = false) {
    if (auto it = regions_.find(start); it != regions_.end()) return it->second;
    const bool entry = start == 0;
    auto* fn = llvm::Function::Create(
        nativeBody ? t_.bodyType : t_.blockType,
        entry ? llvm::Function::ExternalLinkage : llvm::Function::InternalLinkage,
        entry ? prefix_ : prefix_ + "_at" + std::to_string(start), t_.module);
    fn->setUWTableKind(llvm::UWTableKind::Async);  // helpers throw RuntimeError through native frames
    regions_[start] = fn;
    Function f;
    f.fn = fn;
    f.bound = bound;
    lowerRegion(f, start, nativeBody);
    return fn;
  }

 private:
  struct Function {
    llvm::Function* fn = nullptr;
    llvm::Value* helpers = nullptr;
    llvm::Value* vm = nullptr;
    llvm::Value* frame = nullptr;
    llvm::Value* regs = nullptr;
    llvm::Value* lastFired = nullptr;  // exec()'s `lastFired`: did the latest loop fire
    llvm::BasicBlock* entry = nullptr;  // where the stack variables are allocated
    llvm::Value* loops = nullptr;       // meld_native_loop* per slot (those in `bound` are set)
    std::set<std::uint32_t> bound;      // slots bound by a native loop around this code
    std::map<std::uint32_t, llvm::BasicBlock*> blocks;
    std::vector<std::uint32_t> pending;
  };

  llvm::BasicBlock* at(Function& f, std::uint32_t pc) {
    auto [it, fresh] = f.blocks.try_emplace(pc, nullptr);
    if (fresh) {
      it->second = llvm::BasicBlock::Create(t_.context, "pc" + std::to_string(pc), f.fn);
      f.pending.push_back(pc);
    }
    return it->second;
  }

  void lowerRegion(Function& f, std::uint32_t start, bool nativeBody) {
    f.entry = llvm::BasicBlock::Create(t_.context, "entry", f.fn);
    llvm::IRBuilder<> b(f.entry);
    auto arg = f.fn->arg_begin();
    f.helpers = &*arg++;
    f.vm = &*arg++;
    f.frame = &*arg++;
    f.regs = &*arg++;
    f.loops = nativeBody ? static_cast<llvm::Value*>(&*arg)
                         : b.CreateAlloca(b.getPtrTy(), b.getInt32(std::max<std::uint32_t>(block_.slots, 1)), "loops");
    f.lastFired = b.CreateAlloca(b.getInt1Ty(), nullptr, "lastFired");
    b.CreateStore(b.getFalse(), f.lastFired);
    b.CreateBr(at(f, start));
    while (!f.pending.empty()) {
      const std::uint32_t pc = f.pending.back();
      f.pending.pop_back();
      b.SetInsertPoint(f.blocks.at(pc));
      lowerInstruction(f, b, pc);
    }
  }

  std::uint32_t length(std::uint32_t pc) const {
    std::string why;
    const std::size_t len = meldvm::detail::instructionLength(code_, pc, why);
    if (len == 0) throw NativeError("block '" + block_.label + "': " + why);  // verified: cannot happen
    return std::uint32_t(len);
  }

  // ---- helpers and registers ----
  // The helper table is constant while a program runs: its loads may be merged and hoisted.
  llvm::Value* invariantLoad(llvm::IRBuilder<>& b, llvm::Value* address) {
    llvm::LoadInst* load = b.CreateLoad(b.getPtrTy(), address);
    load->setMetadata(llvm::LLVMContext::MD_invariant_load, llvm::MDNode::get(t_.context, {}));
    return load;
  }
  llvm::Value* helper(Function& f, llvm::IRBuilder<>& b, Helper h) {
    return invariantLoad(b, b.CreateStructGEP(t_.helpersType, f.helpers, h));
  }
  llvm::Value* reg(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {
    return b.CreateConstInBoundsGEP1_64(b.getInt64Ty(), f.regs, r);
  }
  llvm::Value* loadReg(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {
    return b.CreateLoad(b.getInt64Ty(), reg(f, b, r));
  }
  llvm::Value* loadInt(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {  // Value::asInt
    return b.CreateTrunc(loadReg(f, b, r), b.getInt32Ty());
  }
  llvm::Value* loadFloat(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {  // Value::asFloat
    return b.CreateBitCast(loadReg(f, b, r), b.getDoubleTy());
  }
  void storeInt(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* i32) {  // fromInt
    b.CreateStore(b.CreateSExt(i32, b.getInt64Ty()), reg(f, b, r));
  }
  void storeFloat(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* d) {
    b.CreateStore(b.CreateBitCast(d, b.getInt64Ty()), reg(f, b, r));
  }
  void storeBool(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* i1) {
    b.CreateStore(b.CreateZExt(i1, b.getInt64Ty()), reg(f, b, r));
  }
  void step(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {  // steps[opcode](vm, frame, pc)
    llvm::Value* entry = b.CreateConstInBoundsGEP1_64(b.getPtrTy(), helper(f, b, kSteps), code_[pc]);
    b.CreateCall(t_.stepType, invariantLoad(b, entry), {f.vm, f.frame, b.getInt32(pc)});
    b.CreateBr(at(f, pc + length(pc)));
  }
  void branch(Function& f, llvm::IRBuilder<>& b, llvm::Value* cond, std::uint32_t yes, std::uint32_t no) {
    b.CreateCondBr(cond, at(f, yes), at(f, no));
  }
  void ret(llvm::IRBuilder<>& b, Status s) { b.CreateRet(b.getInt32(s)); }

  // A stack variable of the function (in its entry block, where mem2reg promotes it).
  llvm::AllocaInst* local(Function& f, llvm::Type* type, const char* name) {
    llvm::IRBuilder<> e(f.entry, f.entry->getFirstInsertionPt());
    return e.CreateAlloca(type, nullptr, name);
  }
  llvm::BasicBlock* newBlock(Function& f, const std::string& name) {
    return llvm::BasicBlock::Create(t_.context, name, f.fn);
  }

  // What loop_begin said about a loop (meld_native_loop), read where it is needed.
  struct LoopView {
    llvm::Value* slots;   // the frame's meld_native_slot array
    llvm::Value* words;   // where the predicate's slot array is
    llvm::Value* stride;  // i64
    llvm::Value* argOffset;
  };
  LoopView loadLoopView(llvm::IRBuilder<>& b, llvm::Value* info) {
    auto field = [&](LoopField k, llvm::Type* type) {
      return b.CreateLoad(type, b.CreateStructGEP(t_.loopStructType, info, k));
    };
    return {field(kLoopSlots, b.getPtrTy()), field(kLoopWords, b.getPtrTy()),
            b.CreateZExt(field(kLoopStride, b.getInt32Ty()), b.getInt64Ty()),
            b.CreateZExt(field(kLoopArgOffset, b.getInt32Ty()), b.getInt64Ty())};
  }
  // The loop that bound slot s around this code (s is in f.bound).
  LoopView loopView(Function& f, llvm::IRBuilder<>& b, std::uint32_t s) {
    return loadLoopView(b, b.CreateLoad(b.getPtrTy(), b.CreateConstInBoundsGEP1_64(b.getPtrTy(), f.loops, s)));
  }
  llvm::Value* slotField(llvm::IRBuilder<>& b, llvm::Value* slots, std::uint32_t s, SlotField k) {
    return b.CreateStructGEP(t_.slotType, b.CreateConstInBoundsGEP1_64(t_.slotType, slots, s), k);
  }
  // The address of word w of fact `fact` (the array is read each time: a body may grow it).
  llvm::Value* factWord(llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact, llvm::Value* w) {
    llvm::Value* array = b.CreateLoad(b.getPtrTy(), loop.words);
    llvm::Value* index = b.CreateAdd(b.CreateMul(b.CreateZExt(fact, b.getInt64Ty()), loop.stride), w);
    return b.CreateInBoundsGEP(b.getInt64Ty(), array, index);
  }
  llvm::Value* highHalf(llvm::IRBuilder<>& b, llvm::Value* fact, const LoopView& loop, llvm::Value* w) {
    llvm::Value* word = b.CreateLoad(b.getInt64Ty(), factWord(b, loop, fact, w));
    return b.CreateTrunc(b.CreateLShr(word, 32), b.getInt32Ty());
  }
  llvm::Value* factCount(llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact) {
    return highHalf(b, fact, loop, b.getInt64(1));  // 0: consumed
  }

  // The loop's end: the same status as the interpreter's (lastFired, or return when stopping).
  void endLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc, llvm::Value* fired, llvm::Value* stopping) {
    b.CreateStore(fired, f.lastFired);
    llvm::BasicBlock* stop = newBlock(f, "stop");
    b.CreateCondBr(stopping, stop, at(f, code_[pc + length(pc) - 1]));
    b.SetInsertPoint(stop);
    ret(b, kReturn);
  }

  void lowerLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
    if (Opcode(code_[pc]) != Opcode::ITER_SORTED) return lowerNativeLoop(f, b, pc);
    llvm::Function* body = region(pc + length(pc));  // lowers the body (a separate function) first
    llvm::Value* r =
        b.CreateCall(t_.loopType, helper(f, b, kLoop), {f.helpers, f.vm, f.frame, b.getInt32(pc), body});
    endLoop(f, b, pc, b.CreateICmpEQ(r, b.getInt32(kFired)), b.CreateICmpEQ(r, b.getInt32(kReturn)));
  }

  // ITER and ITER_KEY: the VM binds the slot and finds the first fact (loop_begin); the facts are
  // stepped through here, in the order, with the skips and the counts of Interpreter::loop.
  void lowerNativeLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
    const std::uint32_t pred = code_[pc + 1], slot = code_[pc + 2], flags = code_[pc + 3];
    std::set<std::uint32_t> bound = f.bound;
    bound.insert(slot);
    llvm::Function* body = region(pc + length(pc), bound, true);
    llvm::Type* i32 = b.getInt32Ty();
    llvm::Type* i64 = b.getInt64Ty();
    llvm::AllocaInst* info = local(f, t_.loopStructType, "loop");
    llvm::AllocaInst* factVar = local(f, i32, "fact");
    llvm::AllocaInst* triedVar = local(f, i64, "tried");
    llvm::AllocaInst* firedVar = local(f, b.getInt1Ty(), "fired");
    b.CreateCall(t_.loopBeginType, helper(f, b, kLoopBegin), {f.vm, f.frame, b.getInt32(pc), info});
    b.CreateStore(info, b.CreateConstInBoundsGEP1_64(b.getPtrTy(), f.loops, slot));
    const LoopView loop = loadLoopView(b, info);
    auto field = [&](LoopField k, llvm::Type* type) {
      return b.CreateLoad(type, b.CreateStructGEP(t_.loopStructType, info, k));
    };
    llvm::Value* stopFlag = field(kLoopStop, b.getPtrTy());
    llvm::Value* sharedStop = field(kLoopSharedStop, b.getPtrTy());
    llvm::Value* nextWord = b.CreateZExt(field(kLoopNextWord, i32), i64);
    b.CreateStore(field(kLoopFirst, i32), factVar);
    b.CreateStore(b.getInt64(0), triedVar);
    b.CreateStore(b.getFalse(), firedVar);
    auto stopping = [&] {
      llvm::LoadInst* shared = b.CreateLoad(b.getInt8Ty(), sharedStop);
      shared->setAtomic(llvm::AtomicOrdering::Monotonic);  // another thread writes it
      return b.CreateOr(b.CreateICmpNE(b.CreateLoad(b.getInt8Ty(), stopFlag), b.getInt8(0)),
                        b.CreateICmpNE(shared, b.getInt8(0)));
    };

    llvm::BasicBlock* header = newBlock(f, "loop" + std::to_string(pc));
    llvm::BasicBlock* advance = newBlock(f, "advance" + std::to_string(pc));
    llvm::BasicBlock* exit = newBlock(f, "exit" + std::to_string(pc));
    b.CreateBr(header);
    b.SetInsertPoint(header);
    llvm::Value* fact = b.CreateLoad(i32, factVar);
    llvm::BasicBlock* visit = newBlock(f, "visit" + std::to_string(pc));
    b.CreateCondBr(b.CreateICmpEQ(fact, b.getInt32(MELD_NATIVE_NO_FACT)), exit, visit);
    b.SetInsertPoint(visit);
    b.CreateStore(b.CreateAdd(b.CreateLoad(i64, triedVar), b.getInt64(1)), triedVar);
    if (flags & meldvm::kIterLinear) {  // skipFact: consumed, or bound by an enclosing loop (§6.4.3)
      llvm::BasicBlock* live = newBlock(f, "live");
      b.CreateCondBr(b.CreateICmpEQ(factCount(b, loop, fact), b.getInt32(0)), advance, live);
      b.SetInsertPoint(live);
      for (std::uint32_t s = 0; s < slot; ++s) {
        const std::int64_t known = slotPredicate(s);
        if (known >= 0 && known != pred) continue;  // never holds a fact of this predicate
        llvm::Value* same = b.CreateAnd(
            b.CreateICmpEQ(b.CreateLoad(i32, slotField(b, loop.slots, s, kSlotFact)), fact),
            b.CreateAnd(b.CreateICmpEQ(b.CreateLoad(i32, slotField(b, loop.slots, s, kSlotPred)), b.getInt32(pred)),
                        b.CreateIsNull(b.CreateLoad(b.getPtrTy(), slotField(b, loop.slots, s, kSlotFixed)))));
        llvm::BasicBlock* other = newBlock(f, "other");
        b.CreateCondBr(same, advance, other);
        b.SetInsertPoint(other);
      }
    }
    b.CreateStore(fact, slotField(b, loop.slots, slot, kSlotFact));
    llvm::Value* r = b.CreateCall(t_.bodyType, body, {f.helpers, f.vm, f.frame, f.regs, f.loops});
    llvm::Value* firedNow = b.CreateICmpEQ(r, b.getInt32(kFired));
    b.CreateStore(b.CreateOr(b.CreateLoad(b.getInt1Ty(), firedVar), firedNow), firedVar);
    llvm::Value* leave = stopping();
    if (flags & meldvm::kIterReturnOnFire) leave = b.CreateOr(leave, firedNow);
    b.CreateCondBr(leave, exit, advance);
    b.SetInsertPoint(advance);
    b.CreateStore(highHalf(b, b.CreateLoad(i32, factVar), loop, nextWord), factVar);
    b.CreateBr(header);

    b.SetInsertPoint(exit);
    b.CreateCall(t_.loopEndType, helper(f, b, kLoopEnd), {f.vm, f.frame, b.getInt32(pc), b.CreateLoad(i64, triedVar)});
    endLoop(f, b, pc, b.CreateLoad(b.getInt1Ty(), firedVar), stopping());
  }

  void lowerInstruction(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
    const std::uint32_t* c = code_.data() + pc;
    const std::uint32_t next = pc + length(pc);
    auto intOp = [&](auto&& op) {
      storeInt(f, b, c[1], op(loadInt(f, b, c[2]), loadInt(f, b, c[3])));
      b.CreateBr(at(f, next));
    };
    auto floatOp = [&](auto&& op) {
      storeFloat(f, b, c[1], op(loadFloat(f, b, c[2]), loadFloat(f, b, c[3])));
      b.CreateBr(at(f, next));
    };
    auto intCompare = [&](llvm::CmpInst::Predicate p) {
      storeBool(f, b, c[1], b.CreateICmp(p, loadInt(f, b, c[2]), loadInt(f, b, c[3])));
      b.CreateBr(at(f, next));
    };
    auto floatCompare = [&](llvm::CmpInst::Predicate p) {
      storeBool(f, b, c[1], b.CreateFCmp(p, loadFloat(f, b, c[2]), loadFloat(f, b, c[3])));
      b.CreateBr(at(f, next));
    };
    auto isZero = [&](std::uint32_t r) { return b.CreateICmpEQ(loadReg(f, b, r), b.getInt64(0)); };
    switch (Opcode(c[0])) {
      // ---- control ----
      case Opcode::ITER:
      case Opcode::ITER_KEY:
      case Opcode::ITER_SORTED:
        return lowerLoop(f, b, pc);
      case Opcode::NEXT:
        return (void)b.CreateRet(b.CreateZExt(b.CreateLoad(b.getInt1Ty(), f.lastFired), b.getInt32Ty()));
      case Opcode::FIRE:
      case Opcode::CFIRE:
        return lowerFire(f, b, pc, Opcode(c[0]) == Opcode::FIRE);
      case Opcode::RET:
        return ret(b, kReturn);
      case Opcode::RET_IF_UPDATED: {
        llvm::Value* updated = b.CreateCall(t_.updatedType, helper(f, b, kUpdated), {f.frame});
        llvm::BasicBlock* stop = llvm::BasicBlock::Create(t_.context, "updated", f.fn);
        b.CreateCondBr(b.CreateICmpNE(updated, b.getInt32(0)), stop, at(f, next));
        b.SetInsertPoint(stop);
        return ret(b, kReturn);
      }
      case Opcode::TEST: {
        if (inSlotRun(pc, c[1])) return lowerSlotRun(f, b, pc);
        llvm::Value* equal = b.CreateCall(t_.testType, helper(f, b, kTest), {f.vm, f.frame, b.getInt32(pc)});
        return branch(f, b, b.CreateICmpNE(equal, b.getInt32(0)), next, c[4]);
      }
      case Opcode::JF:
        return branch(f, b, isZero(c[1]), c[2], next);
      case Opcode::JT:
        return branch(f, b, isZero(c[1]), next, c[2]);
      case Opcode::JMP:
        return (void)b.CreateBr(at(f, c[1]));
      case Opcode::JNIL:
        return branch(f, b, isZero(c[1]), c[2], next);
      case Opcode::JNOTNIL:
        return branch(f, b, isZero(c[1]), next, c[2]);
      // ---- unboxed registers, inline (the same results as the interpreter's cases) ----
      case Opcode::MOVI:
        storeInt(f, b, c[1], b.getInt32(c[2]));
        return (void)b.CreateBr(at(f, next));
      case Opcode::MOVF:
        b.CreateStore(b.getInt64(std::uint64_t(c[2]) | (std::uint64_t(c[3]) << 32)), reg(f, b, c[1]));
        return (void)b.CreateBr(at(f, next));
      case Opcode::MOVB:
        b.CreateStore(b.getInt64(c[2] != 0), reg(f, b, c[1]));
        return (void)b.CreateBr(at(f, next));
      case Opcode::MOVN:
        b.CreateStore(b.getInt64(c[2]), reg(f, b, c[1]));
        return (void)b.CreateBr(at(f, next));
      case Opcode::ADDI:  // wrapping 32-bit arithmetic (arith.hpp)
        return intOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateAdd(x, y); });
      case Opcode::SUBI:
        return intOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateSub(x, y); });
      case Opcode::MULI:
        return intOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateMul(x, y); });
      case Opcode::MINI:
        return intOp([&](llvm::Value* x, llvm::Value* y) {
          return b.CreateBinaryIntrinsic(llvm::Intrinsic::smin, x, y);
        });
      case Opcode::ADDF:
        return floatOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateFAdd(x, y); });
      case Opcode::SUBF:
        return floatOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateFSub(x, y); });
      case Opcode::MULF:
        return floatOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateFMul(x, y); });
      case Opcode::DIVF:
        return floatOp([&](llvm::Value* x, llvm::Value* y) { return b.CreateFDiv(x, y); });
      case Opcode::I2F:
        storeFloat(f, b, c[1], b.CreateSIToFP(loadInt(f, b, c[2]), b.getDoubleTy()));
        return (void)b.CreateBr(at(f, next));
      case Opcode::LTI:
        return intCompare(llvm::CmpInst::ICMP_SLT);
      case Opcode::LEI:
        return intCompare(llvm::CmpInst::ICMP_SLE);
      case Opcode::GTI:
        return intCompare(llvm::CmpInst::ICMP_SGT);
      case Opcode::GEI:
        return intCompare(llvm::CmpInst::ICMP_SGE);
      case Opcode::LTF:  // ordered: false with a NaN, as C++'s <
        return floatCompare(llvm::CmpInst::FCMP_OLT);
      case Opcode::LEF:
        return floatCompare(llvm::CmpInst::FCMP_OLE);
      case Opcode::GTF:
        return floatCompare(llvm::CmpInst::FCMP_OGT);
      case Opcode::GEF:
        return floatCompare(llvm::CmpInst::FCMP_OGE);
      case Opcode::NOT:
        storeBool(f, b, c[1], isZero(c[2]));
        return (void)b.CreateBr(at(f, next));
      case Opcode::LOAD:
        return lowerSlotRun(f, b, pc);
      case Opcode::CALL:
        return lowerCall(f, b, pc);
      // ---- the interpreter's code, through the step helper: the fact store, the heap (boxed
      // registers own references), messages, the scheduler, errors ----
      case Opcode::MOV:
      case Opcode::MOVS:
      case Opcode::NIL:
      case Opcode::GLOBAL:
      case Opcode::SETGLOBAL:
      case Opcode::HOST:
      case Opcode::WORLD:
      case Opcode::CPUS:
      case Opcode::THREAD:
      case Opcode::ARG:
      case Opcode::DIVI:  // throws on a zero divisor
      case Opcode::MODI:
      case Opcode::EQ:  // equality by type (strings, lists, structs: by content)
      case Opcode::NE:
      case Opcode::CONS:
      case Opcode::HEAD:
      case Opcode::TAIL:
      case Opcode::STRUCT:
      case Opcode::FIELD:
      case Opcode::CALLF:
      case Opcode::CALLX:
      case Opcode::DERIVE:
      case Opcode::SEND:
      case Opcode::SEND_DELAY:
      case Opcode::UPDATE:
      case Opcode::ACTION:
      case Opcode::AXIOMS:
      case Opcode::NEWNODE:
      case Opcode::SET_PRIORITY:
      case Opcode::ADD_PRIORITY:
      case Opcode::REMOVE_PRIORITY:
      case Opcode::SET_DEFAULT_PRIORITY:
      case Opcode::SCHEDULE_NEXT:
      case Opcode::SET_STATIC:
      case Opcode::SET_MOVING:
      case Opcode::SET_AFFINITY:
      case Opcode::SET_CPU:
      case Opcode::STOP_PROGRAM:
      case Opcode::SEND_THREAD:
        return step(f, b, pc);
      case Opcode::Count:
        break;
    }
    throw NativeError("block '" + block_.label + "': no lowering for opcode " + std::to_string(c[0]));
  }

  bool boxed(std::uint32_t r) const { return program_.types.boxed(block_.registerTypes[r]); }

  // The predicate a loop slot holds facts of, when every loop that binds it has the same one
  // (otherwise, or for a process's trigger slot, unknown: -1).
  std::int64_t slotPredicate(std::uint32_t slot) const {
    auto it = slotPreds_.find(slot);
    return it == slotPreds_.end() ? -1 : it->second;
  }
  // Whether TEST at pc compares an int, bool, node or thread field: then equality is of the bits.
  bool integerTest(std::uint32_t pc) const {
    const std::int64_t p = slotPredicate(code_[pc + 1]);
    if (p < 0) return false;
    const meldvm::TypeKind k = program_.types.kind(program_.predicates[std::size_t(p)].fields[code_[pc + 2]]);
    return k == meldvm::TypeKind::Int || k == meldvm::TypeKind::Bool || k == meldvm::TypeKind::Node ||
           k == meldvm::TypeKind::Thread;
  }
  bool inSlotRun(std::uint32_t pc, std::uint32_t slot) const {
    if (pc >= code_.size() || code_[pc + 1] != slot) return false;
    const Opcode op = Opcode(code_[pc]);
    return op == Opcode::LOAD || (op == Opcode::TEST && integerTest(pc));
  }

  // Reference counts adjusted inline (a boxed value points at its 32-bit count; nil holds none):
  // only a count that would reach zero calls the VM.
  void adjustCount(Function& f, llvm::IRBuilder<>& b, llvm::Value* v, bool retain, std::uint32_t type) {
    llvm::BasicBlock* object = newBlock(f, retain ? "retain" : "release");
    llvm::BasicBlock* done = newBlock(f, retain ? "retained" : "released");
    b.CreateCondBr(b.CreateICmpNE(v, b.getInt64(0)), object, done);
    b.SetInsertPoint(object);
    llvm::Value* count = b.CreateIntToPtr(v, b.getPtrTy());
    llvm::Value* refs = b.CreateLoad(b.getInt32Ty(), count);
    if (retain) {
      b.CreateStore(b.CreateAdd(refs, b.getInt32(1)), count);
      b.CreateBr(done);
    } else {
      llvm::BasicBlock* last = newBlock(f, "last");
      llvm::BasicBlock* more = newBlock(f, "more");
      b.CreateCondBr(b.CreateICmpEQ(refs, b.getInt32(1)), last, more);
      b.SetInsertPoint(last);
      b.CreateCall(t_.releaseLastType, helper(f, b, kReleaseLast), {f.vm, b.getInt32(type), v});
      b.CreateBr(done);
      b.SetInsertPoint(more);
      b.CreateStore(b.CreateSub(refs, b.getInt32(1)), count);
      b.CreateBr(done);
    }
    b.SetInsertPoint(done);
  }
  // Before a boxed register takes `value`: the interpreter's retain, then setReg's release of the
  // old value.
  void setBoxed(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* value) {
    adjustCount(f, b, value, true, block_.registerTypes[r]);
    adjustCount(f, b, loadReg(f, b, r), false, block_.registerTypes[r]);
  }

  // CALL: the built-in's implementation is called directly (builtins[id]) with the registers'
  // values; its result is owned, so a boxed register only lets go of its old value. fabs is inline.
  void lowerCall(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
    const std::uint32_t* c = code_.data() + pc;
    const std::uint32_t dest = c[1], id = c[2], count = c[4];
    if (id == fabsId_) {
      storeFloat(f, b, dest, b.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, loadFloat(f, b, c[5])));
      return (void)b.CreateBr(at(f, pc + length(pc)));
    }
    llvm::Type* argsType = llvm::ArrayType::get(b.getInt64Ty(), std::max<std::uint32_t>(count, 1));
    llvm::AllocaInst* args = local(f, argsType, "args");
    for (std::uint32_t i = 0; i < count; ++i)
      b.CreateStore(loadReg(f, b, c[5 + i]), b.CreateConstInBoundsGEP2_32(argsType, args, 0, i));
    llvm::Value* entry = b.CreateConstInBoundsGEP1_64(b.getPtrTy(), helper(f, b, kBuiltins), id);
    llvm::Value* result = b.CreateCall(t_.builtinType, invariantLoad(b, entry),
                                       {f.vm, args, b.getInt32(count), b.getInt32(c[3])});
    if (boxed(dest)) adjustCount(f, b, loadReg(f, b, dest), false, block_.registerTypes[dest]);
    b.CreateStore(result, reg(f, b, dest));
    b.CreateBr(at(f, pc + length(pc)));
  }

  // LOADs and TESTs of integer-like fields, one after the other on the same slot: its arguments
  // are looked up once and read in place (nothing stores a fact in between: a release that frees
  // a value touches the heap, not the fact store).
  void lowerSlotRun(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
    const std::uint32_t slot = code_[pc + 1];
    llvm::Value* args;
    if (f.bound.count(slot)) {  // a native loop's fact: its arguments are read in the table
      const LoopView loop = loopView(f, b, slot);
      llvm::Value* fact = b.CreateLoad(b.getInt32Ty(), slotField(b, loop.slots, slot, kSlotFact));
      args = factWord(b, loop, fact, loop.argOffset);
    } else {
      args = b.CreateCall(t_.slotArgsType, helper(f, b, kSlotArgs), {f.vm, f.frame, b.getInt32(slot)});
    }
    for (; inSlotRun(pc, slot); pc += length(pc)) {
      llvm::Value* field =
          b.CreateLoad(b.getInt64Ty(), b.CreateConstInBoundsGEP1_64(b.getInt64Ty(), args, code_[pc + 2]));
      if (Opcode(code_[pc]) == Opcode::LOAD) {
        if (boxed(code_[pc + 3])) setBoxed(f, b, code_[pc + 3], field);
        b.CreateStore(field, reg(f, b, code_[pc + 3]));
        continue;
      }
      llvm::BasicBlock* equal = llvm::BasicBlock::Create(t_.context, "equal" + std::to_string(pc), f.fn);
      b.CreateCondBr(b.CreateICmpEQ(field, loadReg(f, b, code_[pc + 3])), equal, at(f, code_[pc + 4]));
      b.SetInsertPoint(equal);
    }
    b.CreateBr(at(f, pc));
  }

  // FIRE and CFIRE: the interpreter's fire(), reading the slots of native loops in place (the VM is
  // called only for a fact to consume, or for a slot a native loop did not bind).
  void lowerFire(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc, bool rule) {
    for (auto it = consumingSlots_.lower_bound(code_[pc + 1]); it != consumingSlots_.end(); ++it) {
      const std::uint32_t s = *it;
      llvm::Value* slot = b.getInt32(s);
      if (!f.bound.count(s)) {
        b.CreateCall(t_.consumeType, helper(f, b, kConsume), {f.vm, f.frame, slot});
        continue;
      }
      const LoopView loop = loopView(f, b, s);
      llvm::Value* flags = b.CreateLoad(b.getInt32Ty(), slotField(b, loop.slots, s, kSlotFlags));
      llvm::Value* fact = b.CreateLoad(b.getInt32Ty(), slotField(b, loop.slots, s, kSlotFact));
      llvm::BasicBlock *bound = newBlock(f, "bound"), *call = newBlock(f, "consume"), *done = newBlock(f, "consumed");
      b.CreateCondBr(b.CreateAnd(b.CreateICmpNE(b.CreateAnd(flags, b.getInt32(meldvm::kIterConsume)), b.getInt32(0)),
                                 b.CreateICmpNE(fact, b.getInt32(MELD_NATIVE_NO_FACT))),
                     bound, done);
      b.SetInsertPoint(bound);
      b.CreateCondBr(b.CreateICmpEQ(factCount(b, loop, fact), b.getInt32(0)), done, call);
      b.SetInsertPoint(call);
      b.CreateCall(t_.consumeType, helper(f, b, kConsume), {f.vm, f.frame, slot});
      b.CreateBr(done);
      b.SetInsertPoint(done);
    }
    if (rule) b.CreateCall(t_.ruleFiredType, helper(f, b, kRuleFired), {f.vm});
    ret(b, rule ? kFired : kNotFired);
  }

  NativeTypes& t_;
  const meldvm::Program& program_;
  std::set<std::uint32_t> consumingSlots_;  // slots some loop binds with kIterConsume
  const std::uint32_t fabsId_ = meldvm::findBuiltin("fabs")->id;
  std::map<std::uint32_t, std::int64_t> slotPreds_;  // slot -> predicate of every loop binding it
  const meldvm::CodeBlock& block_;
  std::span<const std::uint32_t> code_;
  std::string prefix_;
  std::map<std::uint32_t, llvm::Function*> regions_;  // by the pc each function starts at
};

}  // namespace

NativeTypes::NativeTypes(llvm::Module& m) : module(m), context(m.getContext()) {
  llvm::Type* ptr = llvm::PointerType::getUnqual(context);
  llvm::Type* i32 = llvm::Type::getInt32Ty(context);
  llvm::Type* voidTy = llvm::Type::getVoidTy(context);
  llvm::Type* i64 = llvm::Type::getInt64Ty(context);
  helpersType = llvm::StructType::create(context, {i32, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr},
                                         "meld_native_helpers");
  loopStructType = llvm::StructType::create(context, {ptr, ptr, ptr, ptr, i32, i32, i32, i32}, "meld_native_loop");
  slotType = llvm::StructType::create(context, {i32, i32, i32, i32, ptr}, "meld_native_slot");
  loopBeginType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32, ptr}, false);
  loopEndType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32, i64}, false);
  blockType = llvm::FunctionType::get(i32, {ptr, ptr, ptr, ptr}, false);
  bodyType = llvm::FunctionType::get(i32, {ptr, ptr, ptr, ptr, ptr}, false);
  builtinType = llvm::FunctionType::get(i64, {ptr, ptr, i32, i32}, false);
  loopType = llvm::FunctionType::get(i32, {ptr, ptr, ptr, i32, ptr}, false);
  stepType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32}, false);
  testType = llvm::FunctionType::get(i32, {ptr, ptr, i32}, false);
  consumeType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32}, false);
  updatedType = llvm::FunctionType::get(i32, {ptr}, false);
  slotArgsType = llvm::FunctionType::get(ptr, {ptr, ptr, i32}, false);
  releaseLastType = llvm::FunctionType::get(voidTy, {ptr, i32, i64}, false);
  ruleFiredType = llvm::FunctionType::get(voidTy, {ptr}, false);
}

llvm::Function* lowerBlock(NativeTypes& types, const meldvm::Program& program, const meldvm::CodeBlock& block,
                           const std::string& name, bool process) {
  return RegionLowering(types, program, block, name, process).region(0);
}

}  // namespace meldc::native
