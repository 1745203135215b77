// CONS in native code: the cell taken from the heap as Heap::allocate does (its free list of
// 24-byte blocks, else the room left in its slab), written, its head and tail retained, then the
// register's old value released, all inline (native ABI 13, meld_native_heap). Through the step
// helper, which dispatched to Heap::cons, a cell cost n-queens 10 about 123 instructions. The
// helper still makes the cell when the heap has neither a free block nor room (a new slab, the
// blocks other threads freed), and for lists of nodes, whose references some heaps count.
#include "region_lowering.hpp"

namespace meldc::native::detail {

namespace {
constexpr std::uint64_t kCellBytes = 8 * (MELD_NATIVE_LIST_TAIL_WORD + 1);  // count, type, head, tail
}

bool RegionLowering::consInline(std::uint32_t listType) const {
  const meldvm::TypeId element = program_.types.element(listType);
  const meldvm::TypeKind k = program_.types.kind(element);
  return k != meldvm::TypeKind::Node && k != meldvm::TypeKind::Thread;
}

void RegionLowering::lowerCons(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  const std::uint32_t* c = code_.data() + pc;
  const std::uint32_t dest = c[1], headReg = c[2], tailReg = c[3], listType = c[4];
  if (!consInline(listType)) return step(f, b, pc);
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  auto heapField = [&](HeapField k) {
    return invariantLoad(b, b.CreateStructGEP(t_.heapType, contextField(f, b, kContextHeap, ptr), k));
  };
  llvm::Value* freeList = heapField(kHeapCellFreeList);
  llvm::Value* bumpAt = heapField(kHeapBump);
  llvm::BasicBlock* fromFree = newBlock(f, "cons.free");
  llvm::BasicBlock* tryBump = newBlock(f, "cons.bump?");
  llvm::BasicBlock* fromBump = newBlock(f, "cons.bump");
  llvm::BasicBlock* viaVm = newBlock(f, "cons.vm");
  llvm::BasicBlock* made = newBlock(f, "cons.made");
  llvm::Value* first = b.CreateLoad(ptr, freeList);
  b.CreateCondBr(b.CreateIsNotNull(first), fromFree, tryBump);
  b.SetInsertPoint(fromFree);
  // The next allocation's block was freed long ago and is often cold: fetched now, as
  // Heap::allocate does.
  llvm::Value* second = b.CreateLoad(ptr, first);
  b.CreateStore(second, freeList);
  b.CreateIntrinsic(llvm::Intrinsic::prefetch, {ptr}, {second, b.getInt32(1), b.getInt32(3), b.getInt32(1)});
  b.CreateBr(made);
  b.SetInsertPoint(tryBump);
  llvm::Value* bump = b.CreateLoad(ptr, bumpAt);
  llvm::Value* room = b.CreateSub(b.CreatePtrToInt(b.CreateLoad(ptr, heapField(kHeapBumpEnd)), i64),
                                  b.CreatePtrToInt(bump, i64));
  b.CreateCondBr(b.CreateICmpUGE(room, b.getInt64(kCellBytes)), fromBump, viaVm);
  b.SetInsertPoint(fromBump);
  b.CreateStore(b.CreateConstInBoundsGEP1_64(b.getInt8Ty(), bump, kCellBytes), bumpAt);
  b.CreateBr(made);
  b.SetInsertPoint(viaVm);
  step(f, b, pc);
  b.SetInsertPoint(made);
  llvm::PHINode* cell = b.CreatePHI(ptr, 2, "cell");
  cell->addIncoming(first, fromFree);
  cell->addIncoming(bump, fromBump);
  for (auto [field, add] : {std::pair{kHeapLive, std::uint64_t(1)}, std::pair{kHeapBytesInUse, kCellBytes}}) {
    llvm::Value* counter = heapField(field);
    b.CreateStore(b.CreateAdd(b.CreateLoad(i64, counter), b.getInt64(add)), counter);
  }
  llvm::Value* head = loadReg(f, b, headReg);
  llvm::Value* tail = loadReg(f, b, tailReg);
  b.CreateStore(b.getInt32(1), cell);  // the count: the register's reference
  b.CreateStore(b.getInt32(listType), b.CreateConstInBoundsGEP1_64(i32, cell, 1));
  b.CreateStore(head, b.CreateConstInBoundsGEP1_64(i64, cell, MELD_NATIVE_LIST_HEAD_WORD));
  b.CreateStore(tail, b.CreateConstInBoundsGEP1_64(i64, cell, MELD_NATIVE_LIST_TAIL_WORD));
  // The cell's references, taken before the register lets go of its old value, which may be the
  // tail itself (`L = [X | L]`).
  const meldvm::TypeId element = program_.types.element(listType);
  if (program_.types.boxed(element)) adjustCount(f, b, head, true, element);
  adjustCount(f, b, tail, true, listType);
  adjustCount(f, b, loadReg(f, b, dest), false, block_.registerTypes[dest]);
  b.CreateStore(b.CreatePtrToInt(cell, i64), reg(f, b, dest));
  b.CreateBr(at(f, pc + length(pc)));
}

}  // namespace meldc::native::detail
