// The lowering of what touches the fact store and the heap: loops (native for ITER and ITER_KEY),
// FIRE, runs of LOAD and TEST on a slot, CALL of a built-in, reference counts. What each function
// does is said once, at its declaration in region_lowering.hpp.
#include <llvm/IR/MDBuilder.h>

#include "region_lowering.hpp"

namespace meldc::native::detail {

llvm::Value* RegionLowering::loopField(llvm::IRBuilder<>& b, llvm::Value* info, LoopField k,
                                       llvm::Type* type) {
  return b.CreateLoad(type, b.CreateStructGEP(t_.loopStructType, info, k));
}

RegionLowering::LoopView RegionLowering::loadLoopView(llvm::IRBuilder<>& b, llvm::Value* info) {
  return {loopField(b, info, kLoopSlots, b.getPtrTy()), loopField(b, info, kLoopWords, b.getPtrTy()),
          b.CreateZExt(loopField(b, info, kLoopStride, b.getInt32Ty()), b.getInt64Ty()),
          b.CreateZExt(loopField(b, info, kLoopArgOffset, b.getInt32Ty()), b.getInt64Ty())};
}

RegionLowering::LoopView RegionLowering::loopView(Function& f, llvm::IRBuilder<>& b, std::uint32_t s) {
  if (const std::int64_t pred = slotPredicate(s); pred >= 0) return tableView(f, b, std::uint32_t(pred));
  return loadLoopView(b, b.CreateLoad(b.getPtrTy(), b.CreateConstInBoundsGEP1_64(b.getPtrTy(), f.loops, s)));
}

RegionLowering::LoopView RegionLowering::tableView(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* table = tableOf(f, b, pred);
  auto invariant = [&](llvm::Type* type, llvm::Value* at) {
    llvm::LoadInst* load = b.CreateLoad(type, at);
    load->setMetadata(llvm::LLVMContext::MD_invariant_load, llvm::MDNode::get(t_.context, {}));
    return load;
  };
  auto tableField = [&](TableField k, llvm::Type* type) {
    return invariant(type, b.CreateStructGEP(t_.tableType, table, k));
  };
  return {invariant(ptr, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameSlots)),
          tableField(kTableWords, ptr), b.CreateZExt(tableField(kTableStride, i32), i64),
          b.CreateZExt(tableField(kTableArgOffset, i32), i64)};
}

llvm::Value* RegionLowering::factWord(llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact,
                                      llvm::Value* w) {
  llvm::Value* array = b.CreateLoad(b.getPtrTy(), loop.words);
  llvm::Value* index = b.CreateAdd(b.CreateMul(b.CreateZExt(fact, b.getInt64Ty()), loop.stride), w);
  return b.CreateInBoundsGEP(b.getInt64Ty(), array, index);
}

llvm::Value* RegionLowering::highHalf(llvm::IRBuilder<>& b, llvm::Value* fact, const LoopView& loop,
                                      llvm::Value* w) {
  llvm::Value* word = b.CreateLoad(b.getInt64Ty(), factWord(b, loop, fact, w));
  return b.CreateTrunc(b.CreateLShr(word, 32), b.getInt32Ty());
}

llvm::Value* RegionLowering::factCount(llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact) {
  return highHalf(b, fact, loop, b.getInt64(1));  // 0: consumed
}

void RegionLowering::endLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc, llvm::Value* fired,
                             llvm::Value* stopping) {
  b.CreateStore(fired, f.lastFired);
  llvm::BasicBlock* stop = newBlock(f, "stop");
  b.CreateCondBr(stopping, stop, at(f, code_[pc + length(pc) - 1]));
  b.SetInsertPoint(stop);
  ret(b, kReturn);
}

void RegionLowering::lowerLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  if (Opcode(code_[pc]) != Opcode::ITER_SORTED) return lowerNativeLoop(f, b, pc);
  llvm::Function* body = region(pc + length(pc));  // lowers the body (a separate function) first
  llvm::Value* r =
      b.CreateCall(t_.loopType, helper(f, b, kLoop), {f.helpers, f.vm, f.frame, b.getInt32(pc), body});
  endLoop(f, b, pc, b.CreateICmpEQ(r, b.getInt32(kFired)), b.CreateICmpEQ(r, b.getInt32(kReturn)));
}

void RegionLowering::lowerNativeLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
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
  // What the loop reads of its table and of the stopping flags is the context's (loop_begin copies
  // it): only a slot that loops of several predicates bind has its view read from `info` by the
  // code inside, so only there is `info` kept in f.loops. (Read back from `info`, which the helper
  // calls see, the view was reloaded again and again in the loops of heat-transfer.)
  const bool viewInMemory = slotPredicate(slot) < 0;
  llvm::Value *first = nullptr, *nextWord = b.getInt64(0);
  if (!(flags & meldvm::kIterThread)) {
    std::tie(first, nextWord) = beginLoop(f, b, pc, info, viewInMemory);
  } else {
    b.CreateCall(t_.loopBeginType, helper(f, b, kLoopBegin), {f.vm, f.frame, b.getInt32(pc), info});
    first = loopField(b, info, kLoopFirst, i32);
    nextWord = b.CreateZExt(loopField(b, info, kLoopNextWord, i32), i64);
  }
  if (viewInMemory) b.CreateStore(info, b.CreateConstInBoundsGEP1_64(b.getPtrTy(), f.loops, slot));
  const LoopView loop = tableView(f, b, pred);
  llvm::Value* stopFlag = contextField(f, b, kContextStop, b.getPtrTy());
  llvm::Value* sharedStop = contextField(f, b, kContextSharedStop, b.getPtrTy());
  b.CreateStore(first, factVar);
  const int fetchDepth = meldvm::detail::listFetchDepth(program_, code_, pc);
  const auto listField = std::uint32_t(fetchDepth >= 0 ? meldvm::detail::firstListField(program_, pred) : 0);
  std::optional<ListPipe> pipe;
  if (fetchDepth > 0 && meldvm::detail::listsStayPut(code_))
    pipe = startListPipeline(f, b, loop, b.CreateLoad(i32, factVar), nextWord, listField);
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
  if (fetchDepth >= 0 && !pipe) fetchListsAhead(f, b, loop, fact, nextWord, listField, fetchDepth);
  if (const auto join = meldvm::detail::keyJoinAt(code_, pc + length(pc), slot))
    fetchKeyAhead(f, b, loop, fact, nextWord, *join);
  if (flags & meldvm::kIterLinear) {  // skipFact: consumed, or bound by an enclosing loop (§6.4.3)
    llvm::BasicBlock* live = newBlock(f, "live");
    b.CreateCondBr(b.CreateICmpEQ(factCount(b, loop, fact), b.getInt32(0)), advance, live);
    b.SetInsertPoint(live);
    for (std::uint32_t s = 0; s < slot; ++s) {
      const std::int64_t known = slotPredicate(s);
      if (known >= 0 && known != pred) continue;  // never holds a fact of this predicate
      llvm::Value* same = b.CreateAnd(
          b.CreateICmpEQ(b.CreateLoad(i32, slotField(b, loop.slots, s, kSlotFact)), fact),
          b.CreateAnd(
              b.CreateICmpEQ(b.CreateLoad(i32, slotField(b, loop.slots, s, kSlotPred)), b.getInt32(pred)),
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
  if (pipe) stepListPipeline(f, b, loop, *pipe, nextWord, listField);
  b.CreateBr(header);

  b.SetInsertPoint(exit);  // the loop's end: the facts tried counted, the slot unbound
  llvm::Value* triedTotal = contextField(f, b, kContextFactsTried, b.getPtrTy());
  b.CreateStore(b.CreateAdd(b.CreateLoad(i64, triedTotal), b.CreateLoad(i64, triedVar)), triedTotal);
  b.CreateStore(b.getInt32(MELD_NATIVE_NO_FACT), slotField(b, loop.slots, slot, kSlotFact));
  endLoop(f, b, pc, b.CreateLoad(b.getInt1Ty(), firedVar), stopping());
}

std::pair<llvm::Value*, llvm::Value*> RegionLowering::beginLoop(Function& f, llvm::IRBuilder<>& b,
                                                                std::uint32_t pc, llvm::Value* info,
                                                                bool fillInfo) {
  const std::uint32_t pred = code_[pc + 1], slot = code_[pc + 2], flags = code_[pc + 3];
  const bool keyed = Opcode(code_[pc]) == Opcode::ITER_KEY;
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::BasicBlock* atLimit = newBlock(f, "begin.limit");
  llvm::BasicBlock* here = newBlock(f, "begin");
  llvm::BasicBlock* begun = newBlock(f, "begun");
  llvm::Value* steps = contextField(f, b, kContextStepsLeft, ptr);
  llvm::Value* left = b.CreateLoad(i64, steps);
  llvm::MDBuilder weights(t_.context);
  llvm::Value* index = nullptr;  // ITER_KEY: the meld_native_field_index of its argument
  if (keyed) {                   // an argument without an integer index of its own: the VM looks the key up
    llvm::BasicBlock* indexed = newBlock(f, "begin.indexed");
    llvm::Value* fields =
        b.CreateLoad(ptr, b.CreateStructGEP(t_.tableType, tableOf(f, b, pred), kTableFields));
    b.CreateCondBr(b.CreateOr(b.CreateICmpEQ(left, b.getInt64(1)), b.CreateIsNull(fields)), atLimit, indexed,
                   weights.createBranchWeights(1, 1 << 20));
    b.SetInsertPoint(indexed);
    index = b.CreateConstInBoundsGEP1_64(t_.fieldIndexType, fields, code_[pc + 4]);
    llvm::Value* integer = b.CreateLoad(i32, b.CreateStructGEP(t_.fieldIndexType, index, kIndexInteger));
    b.CreateCondBr(b.CreateICmpEQ(integer, b.getInt32(0)), atLimit, here,
                   weights.createBranchWeights(1, 1 << 20));
  } else {
    b.CreateCondBr(b.CreateICmpEQ(left, b.getInt64(1)), atLimit, here,
                   weights.createBranchWeights(1, 1 << 20));
  }
  b.SetInsertPoint(atLimit);
  b.CreateCall(t_.loopBeginType, helper(f, b, kLoopBegin), {f.vm, f.frame, b.getInt32(pc), info});
  llvm::Value* helperFirst = loopField(b, info, kLoopFirst, i32);
  llvm::Value* helperNext = b.CreateZExt(loopField(b, info, kLoopNextWord, i32), i64);
  b.CreateBr(begun);

  b.SetInsertPoint(here);
  b.CreateStore(b.CreateSub(left, b.getInt64(1)), steps);
  llvm::Value* slots = b.CreateLoad(ptr, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameSlots));
  llvm::Value* host = b.CreateLoad(i32, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameHost));
  b.CreateStore(b.getInt32(pred), slotField(b, slots, slot, kSlotPred));
  b.CreateStore(host, slotField(b, slots, slot, kSlotNode));
  b.CreateStore(b.getInt32(flags), slotField(b, slots, slot, kSlotFlags));
  b.CreateStore(llvm::ConstantPointerNull::get(b.getPtrTy()), slotField(b, slots, slot, kSlotFixed));
  const LoopView view = tableView(f, b, pred);
  llvm::Value *first = nullptr, *nextWord = b.getInt64(0);
  if (keyed) {
    first = findWithKey(f, b, view, index, host, code_[pc + 4], loadReg(f, b, code_[pc + 5]));
    nextWord =
        b.CreateZExt(b.CreateLoad(i32, b.CreateStructGEP(t_.fieldIndexType, index, kIndexLinkWord)), i64);
  } else {
    first = b.CreateLoad(i32, listHead(f, b, nodeHeads(f, b, host), pred, kHeadFirst));
  }
  if (fillInfo) {
    auto set = [&](LoopField k, llvm::Value* v) {
      b.CreateStore(v, b.CreateStructGEP(t_.loopStructType, info, k));
    };
    set(kLoopSlots, slots);
    set(kLoopWords, view.words);
    set(kLoopStop, contextField(f, b, kContextStop, ptr));
    set(kLoopSharedStop, contextField(f, b, kContextSharedStop, ptr));
    set(kLoopFirst, first);
    set(kLoopStride, b.CreateTrunc(view.stride, i32));
    set(kLoopNextWord, b.CreateTrunc(nextWord, i32));
    set(kLoopArgOffset, b.CreateTrunc(view.argOffset, i32));
  }
  llvm::BasicBlock* nativeEnd = b.GetInsertBlock();
  b.CreateBr(begun);
  b.SetInsertPoint(begun);
  llvm::PHINode* firstPhi = b.CreatePHI(i32, 2, "first");
  firstPhi->addIncoming(helperFirst, atLimit);
  firstPhi->addIncoming(first, nativeEnd);
  if (!keyed) return {firstPhi, b.getInt64(0)};  // a list's links: word 0, whoever began the loop
  llvm::PHINode* nextPhi = b.CreatePHI(i64, 2, "next.word");
  nextPhi->addIncoming(helperNext, atLimit);
  nextPhi->addIncoming(nextWord, nativeEnd);
  return {firstPhi, nextPhi};
}

llvm::Value* RegionLowering::nodeHeads(Function& f, llvm::IRBuilder<>& b, llvm::Value* node) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  // Page node >> shift of the page table, node node & mask of the page.
  llvm::Value* pages = b.CreateLoad(ptr, contextField(f, b, kContextHeadPages, ptr));
  llvm::Value* page = b.CreateLoad(
      ptr,
      b.CreateInBoundsGEP(ptr, pages, b.CreateZExt(b.CreateLShr(node, MELD_NATIVE_HEAD_PAGE_SHIFT), i64)));
  llvm::Value* inPage = b.CreateZExt(b.CreateAnd(node, (1u << MELD_NATIVE_HEAD_PAGE_SHIFT) - 1), i64);
  llvm::Value* perNode = b.CreateZExt(contextField(f, b, kContextHeadsPerNode, i32), i64);
  return b.CreateInBoundsGEP(i32, page,
                             b.CreateMul(inPage, b.CreateMul(perNode, b.getInt64(MELD_NATIVE_HEAD_WORDS))));
}

llvm::Value* RegionLowering::listHead(Function&, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                                      HeadWord w) {
  return b.CreateConstInBoundsGEP1_64(b.getInt32Ty(), heads,
                                      std::uint64_t(pred) * MELD_NATIVE_HEAD_WORDS + w);
}

void RegionLowering::fetchListsAhead(Function& f, llvm::IRBuilder<>& b, const LoopView& loop,
                                     llvm::Value* fact, llvm::Value* nextWord, std::uint32_t field,
                                     int maxDepth) {
  using meldvm::detail::kListFetchAhead;
  llvm::Type* i64 = b.getInt64Ty();
  llvm::BasicBlock* done = newBlock(f, "fetched");
  llvm::Value* ahead = fact;
  for (int k = 1; k <= kListFetchAhead; ++k) {
    ahead = highHalf(b, ahead, loop, nextWord);
    llvm::BasicBlock* there = newBlock(f, "ahead");
    llvm::BasicBlock* next = newBlock(f, "ahead.next");
    b.CreateCondBr(b.CreateICmpEQ(ahead, b.getInt32(MELD_NATIVE_NO_FACT)), done, there);
    b.SetInsertPoint(there);
    if (kListFetchAhead - k > maxDepth) {  // this fact's cell at that depth is not fetched
      b.CreateBr(next);
      b.SetInsertPoint(next);
      continue;
    }
    llvm::Value* cell =
        b.CreateLoad(i64, factWord(b, loop, ahead, b.CreateAdd(loop.argOffset, b.getInt64(field))));
    for (int depth = kListFetchAhead - k; depth > 0; --depth) {
      llvm::BasicBlock* more = newBlock(f, "ahead.cell");
      b.CreateCondBr(b.CreateICmpEQ(cell, b.getInt64(0)), next, more);
      b.SetInsertPoint(more);
      cell = cellWord(b, cell, MELD_NATIVE_LIST_TAIL_WORD);
    }
    // read, high locality, data (a prefetch of address 0 is harmless)
    b.CreateIntrinsic(llvm::Intrinsic::prefetch, {b.getPtrTy()},
                      {b.CreateIntToPtr(cell, b.getPtrTy()), b.getInt32(0), b.getInt32(3), b.getInt32(1)});
    b.CreateBr(next);
    b.SetInsertPoint(next);
  }
  b.CreateBr(done);
  b.SetInsertPoint(done);
}

void RegionLowering::adjustCount(Function& f, llvm::IRBuilder<>& b, llvm::Value* v, bool retain,
                                 std::uint32_t type) {
  llvm::BasicBlock* object = newBlock(f, retain ? "retain" : "release");
  llvm::BasicBlock* done = newBlock(f, retain ? "retained" : "released");
  b.CreateCondBr(b.CreateICmpNE(v, b.getInt64(0)), object, done);
  b.SetInsertPoint(object);
  llvm::Value* count = b.CreateIntToPtr(v, b.getPtrTy());
  llvm::Value* refs = b.CreateLoad(b.getInt32Ty(), count);
  // A count with its top bit set belongs to a value shared between threads (meldvm/heap.hpp):
  // it changes atomically, and dropping a reference to it goes through the VM.
  llvm::Value* shared = b.CreateICmpSLT(refs, b.getInt32(0));
  if (retain) {
    llvm::BasicBlock* atomic = newBlock(f, "retain.shared");
    llvm::BasicBlock* plain = newBlock(f, "retain.private");
    b.CreateCondBr(shared, atomic, plain);
    b.SetInsertPoint(atomic);
    b.CreateAtomicRMW(llvm::AtomicRMWInst::Add, count, b.getInt32(1), llvm::MaybeAlign(4),
                      llvm::AtomicOrdering::Monotonic);
    b.CreateBr(done);
    b.SetInsertPoint(plain);
    b.CreateStore(b.CreateAdd(refs, b.getInt32(1)), count);
    b.CreateBr(done);
  } else {
    llvm::BasicBlock* slow = newBlock(f, "last");
    llvm::BasicBlock* more = newBlock(f, "more");
    b.CreateCondBr(b.CreateOr(b.CreateICmpEQ(refs, b.getInt32(1)), shared), slow, more);
    b.SetInsertPoint(slow);
    b.CreateCall(t_.releaseLastType, helper(f, b, kReleaseLast), {f.vm, b.getInt32(type), v});
    b.CreateBr(done);
    b.SetInsertPoint(more);
    b.CreateStore(b.CreateSub(refs, b.getInt32(1)), count);
    b.CreateBr(done);
  }
  b.SetInsertPoint(done);
}

void RegionLowering::setBoxed(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* value) {
  adjustCount(f, b, value, true, block_.registerTypes[r]);
  adjustCount(f, b, loadReg(f, b, r), false, block_.registerTypes[r]);
}

void RegionLowering::lowerCall(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  const std::uint32_t* c = code_.data() + pc;
  const std::uint32_t dest = c[1], id = c[2], count = c[4];
  if (id == fabsId_) {
    storeFloat(f, b, dest, b.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, loadFloat(f, b, c[5])));
    return (void)b.CreateBr(at(f, pc + length(pc)));
  }
  if (id == queensId_) {
    llvm::Value *row = loadInt(f, b, c[5]), *list = loadReg(f, b, c[6]);
    const auto site = queensSites_.find(pc);
    storeBool(f, b, dest,
              site == queensSites_.end() ? queensViolation(f, b, row, list)
                                         : cachedQueensViolation(f, b, site->second, row, list));
    return (void)b.CreateBr(at(f, pc + length(pc)));
  }
  llvm::Value* args = gatherArgs(f, b, c + 5, count);
  llvm::Value* entry = b.CreateConstInBoundsGEP1_64(b.getPtrTy(), helper(f, b, kBuiltins), id);
  llvm::Value* result = b.CreateCall(t_.builtinType, invariantLoad(b, entry),
                                     {f.vm, args, b.getInt32(count), b.getInt32(c[3])});
  if (boxed(dest)) adjustCount(f, b, loadReg(f, b, dest), false, block_.registerTypes[dest]);
  b.CreateStore(result, reg(f, b, dest));
  b.CreateBr(at(f, pc + length(pc)));
}

llvm::Value* RegionLowering::gatherArgs(Function& f, llvm::IRBuilder<>& b, const std::uint32_t* regs,
                                        std::uint32_t count) {
  llvm::Type* argsType = llvm::ArrayType::get(b.getInt64Ty(), std::max<std::uint32_t>(count, 1));
  llvm::AllocaInst* args = local(f, argsType, "args");
  for (std::uint32_t i = 0; i < count; ++i)
    b.CreateStore(loadReg(f, b, regs[i]), b.CreateConstInBoundsGEP2_32(argsType, args, 0, i));
  return args;
}

void RegionLowering::lowerFactOut(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  switch (Opcode(code_[pc])) {
    case Opcode::DERIVE:  // P*
      return lowerDerive(f, b, pc);
    case Opcode::SEND:  // Pn*
      return lowerSend(f, b, pc);
    default:  // UPDATE, SX*
      return lowerUpdate(f, b, pc);
  }
}

void RegionLowering::lowerSlotRun(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
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
      forgetQueensRows(f, b, code_[pc + 3]);
      if (boxed(code_[pc + 3])) setBoxed(f, b, code_[pc + 3], field);
      b.CreateStore(field, reg(f, b, code_[pc + 3]));
      continue;
    }
    llvm::BasicBlock* equal = newBlock(f, "equal" + std::to_string(pc));
    b.CreateCondBr(b.CreateICmpEQ(field, loadReg(f, b, code_[pc + 3])), equal, at(f, code_[pc + 4]));
    b.SetInsertPoint(equal);
  }
  b.CreateBr(at(f, pc));
}

void RegionLowering::lowerFire(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc, bool rule) {
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
    llvm::BasicBlock *bound = newBlock(f, "bound"), *call = newBlock(f, "consume"),
                     *done = newBlock(f, "consumed");
    b.CreateCondBr(
        b.CreateAnd(b.CreateICmpNE(b.CreateAnd(flags, b.getInt32(meldvm::kIterConsume)), b.getInt32(0)),
                    b.CreateICmpNE(fact, b.getInt32(MELD_NATIVE_NO_FACT))),
        bound, done);
    b.SetInsertPoint(bound);
    b.CreateCondBr(b.CreateICmpEQ(factCount(b, loop, fact), b.getInt32(0)), done, call);
    b.SetInsertPoint(call);
    consumeFact(f, b, loop, s, fact);
    b.CreateBr(done);
    b.SetInsertPoint(done);
  }
  if (rule) increment(b, contextField(f, b, kContextRulesFired, b.getPtrTy()));
  ret(b, rule ? kFired : kNotFired);
}

void RegionLowering::consumeFact(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, std::uint32_t s,
                                 llvm::Value* fact) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* consumed = contextField(f, b, kContextConsumed, ptr);
  llvm::Value* sizeAt = b.CreateStructGEP(t_.consumedType, consumed, 1);
  llvm::Value* size = b.CreateLoad(i32, sizeAt);
  llvm::Value* capacity = b.CreateLoad(i32, b.CreateStructGEP(t_.consumedType, consumed, 2));
  llvm::BasicBlock* full = newBlock(f, "consume.full");
  llvm::BasicBlock* room = newBlock(f, "consume.room");
  llvm::BasicBlock* done = newBlock(f, "consume.done");
  b.CreateCondBr(b.CreateICmpEQ(size, capacity), full, room,
                 llvm::MDBuilder(t_.context).createBranchWeights(1, 1 << 10));
  b.SetInsertPoint(full);  // the VM grows the array
  b.CreateCall(t_.consumeType, helper(f, b, kConsume), {f.vm, f.frame, b.getInt32(s)});
  b.CreateBr(done);

  b.SetInsertPoint(room);
  const std::int64_t known = slotPredicate(s);
  llvm::Value* pred = known >= 0 ? static_cast<llvm::Value*>(b.getInt32(std::uint32_t(known)))
                                 : b.CreateLoad(i32, slotField(b, loop.slots, s, kSlotPred));
  llvm::Value* entry =
      b.CreateInBoundsGEP(i32, b.CreateLoad(ptr, b.CreateStructGEP(t_.consumedType, consumed, 0)),
                          b.CreateMul(b.CreateZExt(size, b.getInt64Ty()), b.getInt64(3)));
  b.CreateStore(b.CreateLoad(i32, slotField(b, loop.slots, s, kSlotNode)), entry);
  b.CreateStore(pred, b.CreateConstInBoundsGEP1_32(i32, entry, 1));
  b.CreateStore(fact, b.CreateConstInBoundsGEP1_32(i32, entry, 2));
  b.CreateStore(b.CreateAdd(size, b.getInt32(1)), sizeAt);
  // The count, the high half of word 1, is 0: consumed (Database::markConsumed).
  llvm::Value* countWord = factWord(b, loop, fact, b.getInt64(1));
  b.CreateStore(b.CreateAnd(b.CreateLoad(b.getInt64Ty(), countWord), b.getInt64(0xFFFFFFFFu)), countWord);
  increment(b, contextField(f, b, kContextFactsConsumed, ptr));
  increment(b, contextField(f, b, kContextRunConsumed, ptr));
  b.CreateBr(done);
  b.SetInsertPoint(done);
}

}  // namespace meldc::native::detail
