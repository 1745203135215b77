// The end of a rule run in the rule's native code, before it returns to the VM, which did it all
// in Machine::finishRuleRun looking up again, for each fact, the table, the node's list heads and
// the rules over the predicate (about 85 instructions per fact consumed and 100 per fact derived
// of heat-transfer). Here the predicates a rule consumes and derives, and their rules, are known
// when it is compiled:
// - the consumed facts are unlinked (native_abi.h, meld_native_consumed), in the order they were
//   consumed, so the free lists are the VM's; a fact native code does not handle stops it, and
//   the VM unlinks that one and the rest;
// - then the linear facts derived at the host are stored (meld_native_context::derived), in the
//   order they were derived, each making the rules over its predicate candidates; the same stop.
#include <llvm/IR/MDBuilder.h>

#include "region_lowering.hpp"

namespace meldc::native::detail {

std::vector<RegionLowering::PredicateRules> RegionLowering::unlinkedPredicates() const {
  std::vector<PredicateRules> out;
  if (!rule_) return out;  // processes run apart from rule runs: their consumed facts wait for the VM
  for (std::uint32_t s : consumingSlots_) {
    const std::int64_t pred = slotPredicate(s);
    if (pred < 0) continue;
    if (std::any_of(out.begin(), out.end(), [&](const PredicateRules& u) { return u.pred == pred; }))
      continue;
    if (auto triggers = triggersOf(std::uint32_t(pred)))
      out.push_back({std::uint32_t(pred), std::move(*triggers)});
  }
  return out;
}

std::vector<RegionLowering::PredicateRules> RegionLowering::derivedPredicates() const {
  std::vector<PredicateRules> out;
  if (!rule_) return out;
  meldvm::detail::forEachInstruction(code_, [&](std::size_t pc) {
    if (Opcode(code_[pc]) != Opcode::DERIVE) return;
    const std::uint32_t pred = code_[pc + 1];
    const meldvm::PredicateDesc& d = program_.predicates[pred];
    if (!d.linear || d.action || d.thread) return;  // what lowerDerive appends to the derived facts
    if (std::any_of(out.begin(), out.end(), [&](const PredicateRules& u) { return u.pred == pred; })) return;
    if (auto triggers = triggersOf(pred)) out.push_back({pred, std::move(*triggers)});
  });
  return out;
}

llvm::Function* RegionLowering::entry() {
  const std::vector<PredicateRules> unlinked = unlinkedPredicates(), stored = derivedPredicates();
  if (unlinked.empty() && stored.empty()) return region(0);
  wrapsEntry_ = true;
  llvm::Function* run = region(0);
  auto* fn = llvm::Function::Create(t_.blockType, llvm::Function::ExternalLinkage, prefix_, t_.module);
  fn->setUWTableKind(llvm::UWTableKind::Async);  // the rule's helpers may throw through it
  Function f;
  f.fn = fn;
  f.entry = newBlock(f, "entry");
  llvm::IRBuilder<> b(f.entry);
  auto arg = fn->arg_begin();
  f.helpers = &*arg++;
  f.vm = &*arg++;
  f.frame = &*arg++;
  f.regs = &*arg;
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* consumed = contextField(f, b, kContextConsumed, ptr);
  llvm::Value* sizeAt = b.CreateStructGEP(t_.consumedType, consumed, 1);
  // Facts consumed before the rule ran (by a persistent process) are the VM's, and so are the
  // ones after them and the facts derived.
  llvm::Value* before = b.CreateLoad(i32, sizeAt);
  llvm::Value* status = b.CreateCall(t_.blockType, run, {f.helpers, f.vm, f.frame, f.regs});
  llvm::BasicBlock* done = newBlock(f, "done");
  llvm::BasicBlock* some = newBlock(f, "unlink");
  llvm::BasicBlock* none = newBlock(f, "unlinked.none");
  llvm::BasicBlock* store = stored.empty() ? done : newBlock(f, "store");
  llvm::Value* size = b.CreateLoad(i32, sizeAt);
  b.CreateCondBr(b.CreateICmpEQ(before, b.getInt32(0)), none, done);
  b.SetInsertPoint(none);
  b.CreateCondBr(b.CreateICmpEQ(size, b.getInt32(0)), store, unlinked.empty() ? done : some);
  if (!unlinked.empty()) {
    b.SetInsertPoint(some);
    unlinkConsumed(f, b, unlinked, consumed, size, store, done);
  } else {
    some->eraseFromParent();
  }
  if (!stored.empty()) {
    b.SetInsertPoint(store);
    storeDerived(f, b, stored, done);
  }
  b.SetInsertPoint(done);
  b.CreateRet(status);
  return fn;
}

void RegionLowering::recordLoop(Function& f, llvm::IRBuilder<>& b, const Records& records,
                                const std::vector<PredicateRules>& preds, const HandleRecord& handle,
                                const AtEnd& atEnd, llvm::BasicBlock* allDone, llvm::BasicBlock* done) {
  llvm::Type* i8 = b.getInt8Ty();
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::BasicBlock* from = b.GetInsertBlock();
  llvm::BasicBlock* header = newBlock(f, records.name + ".next");
  llvm::BasicBlock* visit = newBlock(f, records.name + ".record");
  llvm::BasicBlock* all = newBlock(f, records.name + ".all");
  llvm::BasicBlock* rest = newBlock(f, records.name + ".rest");
  auto byteOf = [&](llvm::Value* i) { return b.CreateMul(b.CreateZExt(i, i64), b.getInt64(records.bytes)); };
  b.CreateBr(header);
  b.SetInsertPoint(header);
  llvm::PHINode* i = b.CreatePHI(i32, 2, "i");
  i->addIncoming(b.getInt32(0), from);
  b.CreateCondBr(b.CreateICmpEQ(i, records.size), all, visit);
  b.SetInsertPoint(visit);
  llvm::Value* record = b.CreateInBoundsGEP(i8, records.data, byteOf(i));
  llvm::Value* pred = b.CreateLoad(i32, b.CreateConstInBoundsGEP1_64(i8, record, records.predByte));
  llvm::SwitchInst* which = b.CreateSwitch(pred, rest, unsigned(preds.size()));
  for (const PredicateRules& u : preds) {
    llvm::BasicBlock* here = newBlock(f, records.name + ".pred" + std::to_string(u.pred));
    which->addCase(b.getInt32(u.pred), here);
    b.SetInsertPoint(here);
    handle(u, record, rest);
    i->addIncoming(b.CreateAdd(i, b.getInt32(1)), b.GetInsertBlock());
    b.CreateBr(header);
  }
  b.SetInsertPoint(all);
  b.CreateStore(b.getInt32(0), records.sizeAt);
  atEnd(true, records.size);
  b.CreateBr(allDone);
  b.SetInsertPoint(rest);  // record i and those after it are the VM's: moved to the front
  llvm::Value* left = b.CreateSub(records.size, i);
  b.CreateMemMove(records.data, llvm::MaybeAlign(4), b.CreateInBoundsGEP(i8, records.data, byteOf(i)),
                  llvm::MaybeAlign(4), byteOf(left));
  b.CreateStore(left, records.sizeAt);
  atEnd(false, i);
  b.CreateBr(done);
}

void RegionLowering::unlinkConsumed(Function& f, llvm::IRBuilder<>& b,
                                    const std::vector<PredicateRules>& unlinked, llvm::Value* consumed,
                                    llvm::Value* size, llvm::BasicBlock* all, llvm::BasicBlock* done) {
  llvm::Type* i8 = b.getInt8Ty();
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Value* sizeAt = b.CreateStructGEP(t_.consumedType, consumed, 1);
  const Records records{"unlink", b.CreateLoad(b.getPtrTy(), b.CreateStructGEP(t_.consumedType, consumed, 0)),
                        size,     sizeAt,
                        3 * 4,    4};
  recordLoop(
      f, b, records, unlinked,
      [&](const PredicateRules& u, llvm::Value* record, llvm::BasicBlock* vm) {
        llvm::Value* node = b.CreateLoad(i32, record);
        llvm::Value* fact = b.CreateLoad(i32, b.CreateConstInBoundsGEP1_64(i8, record, 8));
        unlinkFact(f, b, u, node, fact, vm);
      },
      [](bool, llvm::Value*) {}, all, done);
}

RegionLowering::TableWords RegionLowering::plainTableOrVm(Function& f, llvm::IRBuilder<>& b,
                                                          std::uint32_t pred, llvm::BasicBlock* vm) {
  llvm::Value* flags =
      b.CreateLoad(b.getInt32Ty(), b.CreateStructGEP(t_.tableType, tableOf(f, b, pred), kTableFlags));
  llvm::Value* plain = b.CreateICmpNE(b.CreateAnd(flags, b.getInt32(MELD_NATIVE_TABLE_PLAIN)), b.getInt32(0));
  llvm::BasicBlock* here = newBlock(f, "plain.table");
  b.CreateCondBr(plain, here, vm, llvm::MDBuilder(t_.context).createBranchWeights(1 << 10, 1));
  b.SetInsertPoint(here);
  return tableWords(f, b, pred);
}

void RegionLowering::unlinkFact(Function& f, llvm::IRBuilder<>& b, const PredicateRules& u, llvm::Value* node,
                                llvm::Value* fact, llvm::BasicBlock* vm) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  const TableWords table = plainTableOrVm(f, b, u.pred, vm);
  auto tableField = [&](TableField k, llvm::Type* type) { return table.field(k, type); };
  llvm::Value* heads = nodeHeads(f, b, node);
  llvm::Value* at = table.word0(fact);
  llvm::Value* links = b.CreateLoad(i64, at);
  llvm::Value* prev = b.CreateTrunc(links, i32);
  connect(f, b, heads, u.pred, table, prev, b.CreateTrunc(b.CreateLShr(links, 32), i32));
  llvm::Value* sizeAt = listHead(f, b, heads, u.pred, kHeadSize);
  llvm::Value* left = b.CreateSub(b.CreateLoad(i32, sizeAt), b.getInt32(1));
  b.CreateStore(left, sizeAt);
  llvm::Value* freeList = tableField(kTableFreeList, ptr);
  b.CreateStore(b.getInt64(0), b.CreateConstInBoundsGEP1_64(i64, at, 1));  // count 0: a free slot
  b.CreateStore(
      b.CreateOr(b.CreateShl(b.CreateZExt(b.CreateLoad(i32, freeList), i64), 32), b.CreateZExt(prev, i64)),
      at);
  b.CreateStore(fact, freeList);
  llvm::Value* live = tableField(kTableLive, ptr);
  b.CreateStore(b.CreateSub(b.CreateLoad(i32, live), b.getInt32(1)), live);
  if (u.triggers.empty()) return;
  // Machine::factRemoved: the node's last fact of the predicate gone, no rule over it is a candidate.
  llvm::BasicBlock* empty = newBlock(f, "unlink.empty");
  llvm::BasicBlock* after = newBlock(f, "unlink.done");
  b.CreateCondBr(b.CreateICmpEQ(left, b.getInt32(0)), empty, after);
  b.SetInsertPoint(empty);
  llvm::Value* ruleWords = b.CreateZExt(contextField(f, b, kContextRuleWords, i32), i64);
  llvm::Value* candidates =
      b.CreateInBoundsGEP(i64, b.CreateLoad(ptr, contextField(f, b, kContextCandidates, ptr)),
                          b.CreateMul(b.CreateZExt(node, i64), ruleWords));
  std::map<std::uint32_t, std::uint64_t> bits;  // by word
  for (const RuleTrigger& t : u.triggers) bits[t.rule / 64] |= std::uint64_t(1) << (t.rule % 64);
  for (const auto& [w, mask] : bits) {
    llvm::Value* word = b.CreateConstInBoundsGEP1_64(i64, candidates, w);
    b.CreateStore(b.CreateAnd(b.CreateLoad(i64, word), b.getInt64(~mask)), word);
  }
  b.CreateBr(after);
  b.SetInsertPoint(after);
}

void RegionLowering::storeDerived(Function& f, llvm::IRBuilder<>& b,
                                  const std::vector<PredicateRules>& stored, llvm::BasicBlock* done) {
  llvm::Type* i8 = b.getInt8Ty();
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* derived = contextField(f, b, kContextDerived, ptr);
  llvm::Value* derivedArgs = contextField(f, b, kContextDerivedArgs, ptr);
  llvm::Value* sizeAt = b.CreateStructGEP(t_.arrayType, derived, 1);
  llvm::Value* size = b.CreateLoad(i32, sizeAt);
  // A stored fact is a step (Machine::countSteps): at the limit the VM stores them, and stops.
  llvm::Value* stepsAt = contextField(f, b, kContextStepsLeft, ptr);
  llvm::Value* steps = b.CreateLoad(i64, stepsAt);
  llvm::BasicBlock* from = newBlock(f, "store.begin");
  b.CreateCondBr(
      b.CreateAnd(b.CreateICmpNE(size, b.getInt32(0)), b.CreateICmpULT(b.CreateZExt(size, i64), steps)), from,
      done);
  b.SetInsertPoint(from);
  llvm::Value* words = b.CreateLoad(ptr, b.CreateStructGEP(t_.arrayType, derivedArgs, 0));
  const Records records{"store",
                        b.CreateLoad(ptr, b.CreateStructGEP(t_.arrayType, derived, 0)),
                        size,
                        sizeAt,
                        sizeof(meld_native_sent_fact),
                        kSentPred};
  recordLoop(
      f, b, records, stored,
      [&](const PredicateRules& u, llvm::Value* record, llvm::BasicBlock* vm) {
        llvm::Value* node = b.CreateLoad(i32, b.CreateConstInBoundsGEP1_64(i8, record, kSentNode));
        llvm::Value* argsWord = b.CreateLoad(i32, b.CreateConstInBoundsGEP1_64(i8, record, kSentArgs));
        storeFact(f, b, u, node, b.CreateInBoundsGEP(i64, words, b.CreateZExt(argsWord, i64)), vm);
      },
      [&](bool all, llvm::Value* stored) {
        b.CreateStore(b.CreateSub(steps, b.CreateZExt(stored, i64)), stepsAt);
        // All stored: the arguments' array is empty too, as the VM leaves it (the records left to
        // the VM keep theirs where they are).
        if (all) b.CreateStore(b.getInt32(0), b.CreateStructGEP(t_.arrayType, derivedArgs, 1));
      },
      done, done);
}

void RegionLowering::storeFact(Function& f, llvm::IRBuilder<>& b, const PredicateRules& u, llvm::Value* node,
                               llvm::Value* args, llvm::BasicBlock* vm) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  // FactTable::insertAdopted's common case: a plain table with a free slot (else the VM grows it).
  const TableWords table = plainTableOrVm(f, b, u.pred, vm);
  auto tableField = [&](TableField k, llvm::Type* type) { return table.field(k, type); };
  llvm::Value* freeList = tableField(kTableFreeList, ptr);
  llvm::BasicBlock* here = newBlock(f, "store.free");
  llvm::MDBuilder weights(t_.context);
  llvm::Value* fact = b.CreateLoad(i32, freeList);
  b.CreateCondBr(b.CreateICmpNE(fact, b.getInt32(MELD_NATIVE_NO_FACT)), here, vm,
                 weights.createBranchWeights(1 << 10, 1));
  b.SetInsertPoint(here);
  llvm::Value* at = table.word0(fact);
  b.CreateStore(b.CreateTrunc(b.CreateLShr(b.CreateLoad(i64, at), 32), i32), freeList);
  llvm::Value* argsAt = b.CreateInBoundsGEP(i64, at, b.CreateZExt(tableField(kTableArgOffset, i32), i64));
  const std::size_t arity = program_.predicates[u.pred].fields.size();
  for (std::size_t k = 0; k < arity; ++k)
    b.CreateStore(b.CreateLoad(i64, b.CreateConstInBoundsGEP1_64(i64, args, k)),
                  b.CreateConstInBoundsGEP1_64(i64, argsAt, k));
  b.CreateStore(b.CreateOr(b.CreateZExt(node, i64), b.getInt64(std::uint64_t(1) << 32)),
                b.CreateConstInBoundsGEP1_64(i64, at, 1));  // one copy, at the node
  // Linked at the end of the node's list (FactTable::fill).
  llvm::Value* heads = nodeHeads(f, b, node);
  linkLast(f, b, heads, u.pred, table, fact);
  llvm::Value* sizeAt = listHead(f, b, heads, u.pred, kHeadSize);
  b.CreateStore(b.CreateAdd(b.CreateLoad(i32, sizeAt), b.getInt32(1)), sizeAt);
  llvm::Value* live = tableField(kTableLive, ptr);
  b.CreateStore(b.CreateAdd(b.CreateLoad(i32, live), b.getInt32(1)), live);
  wakeRules(f, b, heads, node, u.triggers);
}

}  // namespace meldc::native::detail
