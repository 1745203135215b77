// A rule's consumed facts unlinked by its native code when the rule run ends, before it returns to
// the VM (native_abi.h, meld_native_consumed). Machine::finishRuleRun did it for every rule run,
// looking up again for each fact the table, the node's list heads and the rules over the predicate
// (about 85 instructions per fact of heat-transfer); here the predicates a rule consumes and their
// rules are known when it is compiled. The order is the VM's: the facts in the order they were
// consumed, so the free lists are the same; a fact native code does not handle stops it, and the
// VM unlinks that one and the rest.
#include <llvm/IR/MDBuilder.h>

#include "region_lowering.hpp"

namespace meldc::native::detail {

std::vector<RegionLowering::Unlinked> RegionLowering::unlinkedPredicates() const {
  std::vector<Unlinked> out;
  if (!rule_) return out;  // processes run apart from rule runs: their consumed facts wait for the VM
  for (std::uint32_t s : consumingSlots_) {
    const std::int64_t pred = slotPredicate(s);
    if (pred < 0) continue;
    if (std::any_of(out.begin(), out.end(), [&](const Unlinked& u) { return u.pred == pred; })) continue;
    if (auto triggers = triggersOf(std::uint32_t(pred)))
      out.push_back({std::uint32_t(pred), std::move(*triggers)});
  }
  return out;
}

llvm::Function* RegionLowering::entry() {
  const std::vector<Unlinked> unlinked = unlinkedPredicates();
  if (unlinked.empty()) return region(0);
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
  // ones after them.
  llvm::Value* before = b.CreateLoad(i32, sizeAt);
  llvm::Value* status = b.CreateCall(t_.blockType, run, {f.helpers, f.vm, f.frame, f.regs});
  llvm::BasicBlock* done = newBlock(f, "done");
  llvm::BasicBlock* some = newBlock(f, "unlink");
  llvm::Value* size = b.CreateLoad(i32, sizeAt);
  b.CreateCondBr(b.CreateAnd(b.CreateICmpEQ(before, b.getInt32(0)), b.CreateICmpNE(size, b.getInt32(0))),
                 some, done);
  b.SetInsertPoint(some);
  unlinkConsumed(f, b, unlinked, consumed, size, done);
  b.SetInsertPoint(done);
  b.CreateRet(status);
  return fn;
}

void RegionLowering::unlinkConsumed(Function& f, llvm::IRBuilder<>& b, const std::vector<Unlinked>& unlinked,
                                    llvm::Value* consumed, llvm::Value* size, llvm::BasicBlock* done) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* sizeAt = b.CreateStructGEP(t_.consumedType, consumed, 1);
  llvm::Value* facts = b.CreateLoad(ptr, b.CreateStructGEP(t_.consumedType, consumed, 0));
  llvm::BasicBlock* from = b.GetInsertBlock();
  llvm::BasicBlock* header = newBlock(f, "unlink.next");
  llvm::BasicBlock* visit = newBlock(f, "unlink.fact");
  llvm::BasicBlock* all = newBlock(f, "unlink.all");
  llvm::BasicBlock* rest = newBlock(f, "unlink.rest");
  b.CreateBr(header);
  b.SetInsertPoint(header);
  llvm::PHINode* i = b.CreatePHI(i32, 2, "i");
  i->addIncoming(b.getInt32(0), from);
  b.CreateCondBr(b.CreateICmpEQ(i, size), all, visit);
  b.SetInsertPoint(visit);
  llvm::Value* entry = b.CreateInBoundsGEP(i32, facts, b.CreateMul(b.CreateZExt(i, i64), b.getInt64(3)));
  llvm::Value* node = b.CreateLoad(i32, entry);
  llvm::Value* pred = b.CreateLoad(i32, b.CreateConstInBoundsGEP1_32(i32, entry, 1));
  llvm::Value* fact = b.CreateLoad(i32, b.CreateConstInBoundsGEP1_32(i32, entry, 2));
  llvm::SwitchInst* which = b.CreateSwitch(pred, rest, unsigned(unlinked.size()));
  for (const Unlinked& u : unlinked) {
    llvm::BasicBlock* here = newBlock(f, "unlink.pred" + std::to_string(u.pred));
    which->addCase(b.getInt32(u.pred), here);
    b.SetInsertPoint(here);
    unlinkFact(f, b, u, node, fact, rest);
    i->addIncoming(b.CreateAdd(i, b.getInt32(1)), b.GetInsertBlock());
    b.CreateBr(header);
  }
  b.SetInsertPoint(all);
  b.CreateStore(b.getInt32(0), sizeAt);
  b.CreateBr(done);
  // Fact i and those after it are the VM's: moved to the front of the array.
  b.SetInsertPoint(rest);
  llvm::Value* stopped = i;
  llvm::Value* left = b.CreateSub(size, stopped);
  llvm::Value* bytes = b.CreateMul(b.CreateZExt(left, i64), b.getInt64(3 * 4));
  b.CreateMemMove(facts, llvm::MaybeAlign(4),
                  b.CreateInBoundsGEP(i32, facts, b.CreateMul(b.CreateZExt(stopped, i64), b.getInt64(3))),
                  llvm::MaybeAlign(4), bytes);
  b.CreateStore(left, sizeAt);
  b.CreateBr(done);
}

void RegionLowering::unlinkFact(Function& f, llvm::IRBuilder<>& b, const Unlinked& u, llvm::Value* node,
                                llvm::Value* fact, llvm::BasicBlock* vm) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* table =
      b.CreateConstInBoundsGEP1_64(t_.tableType, contextField(f, b, kContextTables, ptr), u.pred);
  auto tableField = [&](TableField k, llvm::Type* type) {
    return b.CreateLoad(type, b.CreateStructGEP(t_.tableType, table, k));
  };
  llvm::Value* plain = b.CreateICmpNE(
      b.CreateAnd(tableField(kTableFlags, i32), b.getInt32(MELD_NATIVE_TABLE_PLAIN)), b.getInt32(0));
  llvm::BasicBlock* here = newBlock(f, "unlink.plain");
  b.CreateCondBr(plain, here, vm, llvm::MDBuilder(t_.context).createBranchWeights(1 << 10, 1));
  b.SetInsertPoint(here);
  llvm::Value* words = b.CreateLoad(ptr, tableField(kTableWords, ptr));
  llvm::Value* stride = b.CreateZExt(tableField(kTableStride, i32), i64);
  auto word0 = [&](llvm::Value* g) {
    return b.CreateInBoundsGEP(i64, words, b.CreateMul(b.CreateZExt(g, i64), stride));
  };
  llvm::Value* heads = nodeHeads(f, b, node);
  llvm::Value* at = word0(fact);
  llvm::Value* links = b.CreateLoad(i64, at);
  llvm::Value* prev = b.CreateTrunc(links, i32);
  llvm::Value* next = b.CreateTrunc(b.CreateLShr(links, 32), i32);
  auto setHalf = [&](llvm::Value* where, llvm::Value* v, bool high) {
    llvm::Value* w = b.CreateLoad(i64, where);
    llvm::Value* v64 = b.CreateZExt(v, i64);
    llvm::Value* kept = b.CreateAnd(w, b.getInt64(high ? 0xFFFFFFFFull : 0xFFFFFFFF00000000ull));
    b.CreateStore(b.CreateOr(kept, high ? b.CreateShl(v64, 32) : v64), where);
  };
  // FactTable::connect(list, prev, next): each end is the list head's or the neighbour's link.
  auto link = [&](llvm::Value* end, HeadWord headWord, const std::function<void()>& neighbour,
                  const std::string& name) {
    llvm::BasicBlock* atHead = newBlock(f, name + ".head");
    llvm::BasicBlock* inside = newBlock(f, name + ".inside");
    llvm::BasicBlock* linked = newBlock(f, name + ".linked");
    b.CreateCondBr(b.CreateICmpEQ(end, b.getInt32(MELD_NATIVE_NO_FACT)), atHead, inside);
    b.SetInsertPoint(atHead);
    b.CreateStore(headWord == kHeadFirst ? next : prev, listHead(f, b, heads, u.pred, headWord));
    b.CreateBr(linked);
    b.SetInsertPoint(inside);
    neighbour();
    b.CreateBr(linked);
    b.SetInsertPoint(linked);
  };
  link(
      prev, kHeadFirst, [&] { setHalf(word0(prev), next, true); }, "unlink.prev");
  link(
      next, kHeadLast, [&] { setHalf(word0(next), prev, false); }, "unlink.after");
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

}  // namespace meldc::native::detail
