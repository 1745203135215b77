// What native code does with a table's indexes (meld_native_field_index): an ITER_KEY's first fact
// looked up in the index's hash table, as FactTable::firstWithKey does (through loop_begin it cost
// new-heat-transfer 147 instructions a loop), and the check that lets an UPDATE of an indexed
// fact change it in place (through the update helper and FactTable::replaceIndexedArgs: 285
// instructions an update).
#include <llvm/IR/MDBuilder.h>

#include <algorithm>

#include "meldvm/key_hash.hpp"
#include "region_lowering.hpp"

namespace meldc::native::detail {

llvm::Value* RegionLowering::foldedKeyHash(llvm::IRBuilder<>& b, llvm::Value* host, llvm::Value* key) {
  namespace kh = meldvm::key_hash;
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Value* h = b.CreateMul(b.CreateAdd(b.CreateZExt(host, i64), b.getInt64(kh::kNodeOffset)),
                               b.getInt64(kh::kNodeMultiplier));
  h = b.CreateMul(b.CreateXor(h, key), b.getInt64(kh::kFieldMultiplier));
  h = b.CreateXor(h, b.CreateLShr(h, kh::kFinalShift));
  return b.CreateTrunc(b.CreateXor(h, b.CreateLShr(h, 32)), b.getInt32Ty());
}

llvm::Value* RegionLowering::findWithKey(Function& f, llvm::IRBuilder<>& b, const LoopView& table,
                                         llvm::Value* index, llvm::Value* host, std::uint32_t field,
                                         llvm::Value* key) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* folded = foldedKeyHash(b, host, key);
  auto indexField = [&](FieldIndexField k, llvm::Type* type) {
    return b.CreateLoad(type, b.CreateStructGEP(t_.fieldIndexType, index, k));
  };

  llvm::BasicBlock* start = b.GetInsertBlock();
  llvm::BasicBlock* probe = newBlock(f, "key.probe");
  llvm::BasicBlock* sameHash = newBlock(f, "key.hash");
  llvm::BasicBlock* onward = newBlock(f, "key.onward");
  llvm::BasicBlock* found = newBlock(f, "key.found");
  llvm::BasicBlock* entry = newBlock(f, "key.entries");
  b.CreateCondBr(b.CreateICmpEQ(b.CreateLoad(i32, indexField(kIndexSize, ptr)), b.getInt32(0)), found, entry);
  b.SetInsertPoint(entry);
  llvm::Value* mask = b.CreateLoad(i32, indexField(kIndexMask, ptr));
  llvm::Value* entries = b.CreateLoad(ptr, indexField(kIndexEntries, ptr));
  llvm::Value* home = b.CreateAnd(folded, mask);
  b.CreateBr(probe);

  b.SetInsertPoint(probe);  // linear probing from the folded hash, as SlotHash::find
  llvm::PHINode* at = b.CreatePHI(i32, 2, "key.at");
  at->addIncoming(home, entry);
  llvm::Value* e = b.CreateLoad(i64, b.CreateInBoundsGEP(i64, entries, b.CreateZExt(at, i64)));
  llvm::Value* fact = b.CreateTrunc(b.CreateLShr(e, 32), i32);
  llvm::Value* empty = b.CreateICmpEQ(fact, b.getInt32(MELD_NATIVE_NO_FACT));
  b.CreateCondBr(b.CreateOr(empty, b.CreateICmpNE(b.CreateTrunc(e, i32), folded)), onward, sameHash);

  b.SetInsertPoint(sameHash);  // the fact's node and argument are the key's
  llvm::Value* node = b.CreateTrunc(b.CreateLoad(i64, factWord(b, table, fact, b.getInt64(1))), i32);
  llvm::Value* arg =
      b.CreateLoad(i64, factWord(b, table, fact, b.CreateAdd(table.argOffset, b.getInt64(field))));
  b.CreateCondBr(b.CreateAnd(b.CreateICmpEQ(node, host), b.CreateICmpEQ(arg, key)), found, onward);

  b.SetInsertPoint(onward);
  llvm::BasicBlock* next = newBlock(f, "key.next");
  b.CreateCondBr(empty, found, next);
  b.SetInsertPoint(next);
  at->addIncoming(b.CreateAnd(b.CreateAdd(at, b.getInt32(1)), mask), next);
  b.CreateBr(probe);

  b.SetInsertPoint(found);
  llvm::PHINode* first = b.CreatePHI(i32, 3, "key.first");
  first->addIncoming(b.getInt32(MELD_NATIVE_NO_FACT), start);
  first->addIncoming(fact, sameHash);
  first->addIncoming(b.getInt32(MELD_NATIVE_NO_FACT), onward);
  return first;
}

void RegionLowering::fetchKeyAhead(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact,
                                   llvm::Value* nextWord, const meldvm::detail::KeyJoin& join) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* next = highHalf(b, fact, loop, nextWord);
  llvm::Value* fields =
      b.CreateLoad(ptr, b.CreateStructGEP(t_.tableType, tableOf(f, b, join.pred), kTableFields));
  llvm::BasicBlock* fetch = newBlock(f, "key.ahead");
  llvm::BasicBlock* on = newBlock(f, "key.ahead.done");
  b.CreateCondBr(
      b.CreateAnd(b.CreateICmpNE(next, b.getInt32(MELD_NATIVE_NO_FACT)), b.CreateIsNotNull(fields)), fetch,
      on);
  b.SetInsertPoint(fetch);
  llvm::Value* index = b.CreateConstInBoundsGEP1_64(t_.fieldIndexType, fields, join.keyArg);
  llvm::BasicBlock* integer = newBlock(f, "key.ahead.integer");  // (else no index there, or no bits hash)
  b.CreateCondBr(b.CreateICmpNE(b.CreateLoad(i32, b.CreateStructGEP(t_.fieldIndexType, index, kIndexInteger)),
                                b.getInt32(0)),
                 integer, on);
  b.SetInsertPoint(integer);
  llvm::Value* key =
      b.CreateLoad(i64, factWord(b, loop, next, b.CreateAdd(loop.argOffset, b.getInt64(join.field))));
  llvm::Value* host = b.CreateLoad(i32, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameHost));
  // Where an empty table's entries are not there, the address is nonsense: a prefetch never faults.
  llvm::Value* entries =
      b.CreateLoad(ptr, b.CreateLoad(ptr, b.CreateStructGEP(t_.fieldIndexType, index, kIndexEntries)));
  llvm::Value* mask =
      b.CreateLoad(i32, b.CreateLoad(ptr, b.CreateStructGEP(t_.fieldIndexType, index, kIndexMask)));
  llvm::Value* home = b.CreateAnd(foldedKeyHash(b, host, key), mask);
  b.CreateIntrinsic(llvm::Intrinsic::prefetch, {ptr},
                    {b.CreateInBoundsGEP(i64, entries, b.CreateZExt(home, i64)), b.getInt32(0), b.getInt32(3),
                     b.getInt32(1)});
  b.CreateBr(on);
  b.SetInsertPoint(on);
}

const std::set<std::uint32_t>& RegionLowering::indexedLinear() {
  if (!indexedLinear_) {
    indexedLinear_.emplace();
    for (const auto& [pred, field] : meldvm::detail::keyLookups(program_)) indexedLinear_->insert(pred);
  }
  return *indexedLinear_;
}

// A MELD_NATIVE_TABLE_KEYED table's fact is updated here only if its index chains stay as they
// are (FactTable::replaceIndexedArgs relinks nothing): each indexed argument keeps its value and,
// when the fact moves to the end of its list, no fact with its key follows it.
void RegionLowering::keysKeptOrVm(Function& f, llvm::IRBuilder<>& b, const TableWords& table,
                                  llvm::Value* fact, llvm::Value* args, std::uint32_t count, bool toBack,
                                  const std::function<void()>& viaVm) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Value* keyed = b.CreateICmpNE(
      b.CreateAnd(table.field(kTableFlags, i32), b.getInt32(MELD_NATIVE_TABLE_KEYED)), b.getInt32(0));
  llvm::BasicBlock* check = newBlock(f, "update.keys");
  llvm::BasicBlock* write = newBlock(f, "update.write");
  llvm::BasicBlock* vm = newBlock(f, "update.keys.vm");
  b.CreateCondBr(keyed, check, write);
  b.SetInsertPoint(check);
  llvm::Value* fields = table.field(kTableFields, b.getPtrTy());
  llvm::Value* word0 = table.word0(fact);
  llvm::Value* argsAt = b.CreateInBoundsGEP(i64, word0, b.CreateZExt(table.field(kTableArgOffset, i32), i64));
  llvm::Type* argsType = llvm::ArrayType::get(i64, std::max<std::uint32_t>(count, 1));
  llvm::Value* kept = b.getTrue();
  for (std::uint32_t i = 0; i < count; ++i) {
    llvm::Value* index = b.CreateConstInBoundsGEP1_64(t_.fieldIndexType, fields, i);
    llvm::Value* linkWord = b.CreateLoad(i32, b.CreateStructGEP(t_.fieldIndexType, index, kIndexLinkWord));
    llvm::Value* same = b.CreateICmpEQ(b.CreateLoad(i64, b.CreateConstInBoundsGEP1_64(i64, argsAt, i)),
                                       b.CreateLoad(i64, b.CreateConstInBoundsGEP2_32(argsType, args, 0, i)));
    if (toBack) {
      llvm::Value* link = b.CreateLoad(i64, b.CreateInBoundsGEP(i64, word0, b.CreateZExt(linkWord, i64)));
      same = b.CreateAnd(same, b.CreateICmpEQ(b.CreateLShr(link, 32), b.getInt64(MELD_NATIVE_NO_FACT)));
    }
    kept = b.CreateAnd(kept, b.CreateOr(b.CreateICmpEQ(linkWord, b.getInt32(0)), same));
  }
  b.CreateCondBr(kept, write, vm, llvm::MDBuilder(t_.context).createBranchWeights(1 << 10, 1));
  b.SetInsertPoint(vm);
  viaVm();
  b.SetInsertPoint(write);
}

}  // namespace meldc::native::detail
