// The fetching ahead of the lists of the facts a native loop visits, carried from one visit to the
// next when the lists stay put (vm/engine/src/list_pipeline.hpp says how; this is the same in
// LLVM IR, so that bytecode and native code fetch alike).
#include "region_lowering.hpp"

namespace meldc::native::detail {

namespace {
using meldvm::detail::kListPipelineFacts;
using meldvm::detail::listPipelineDepth;
}

llvm::Value* RegionLowering::tailOrNull(Function& f, llvm::IRBuilder<>& b, llvm::Value* cell) {
  llvm::BasicBlock* from = b.GetInsertBlock();
  llvm::BasicBlock* load = newBlock(f, "tail");
  llvm::BasicBlock* done = newBlock(f, "tail.done");
  b.CreateCondBr(b.CreateICmpEQ(cell, b.getInt64(0)), done, load);
  b.SetInsertPoint(load);
  llvm::Value* tail = cellWord(b, cell, MELD_NATIVE_LIST_TAIL_WORD);
  b.CreateBr(done);
  b.SetInsertPoint(done);
  llvm::PHINode* phi = b.CreatePHI(b.getInt64Ty(), 2);
  phi->addIncoming(b.getInt64(0), from);
  phi->addIncoming(tail, load);
  return phi;
}

// The next fact of `fact`, and its list's first cell (0 for none), both as for no fact after the
// loop's last one.
std::pair<llvm::Value*, llvm::Value*> RegionLowering::nextWithList(Function& f, llvm::IRBuilder<>& b,
                                                                   const LoopView& loop, llvm::Value* fact,
                                                                   llvm::Value* nextWord,
                                                                   std::uint32_t field) {
  llvm::BasicBlock* from = b.GetInsertBlock();
  llvm::BasicBlock* there = newBlock(f, "pipe.fact");
  llvm::BasicBlock* done = newBlock(f, "pipe.fact.done");
  b.CreateCondBr(b.CreateICmpEQ(fact, b.getInt32(MELD_NATIVE_NO_FACT)), done, there);
  b.SetInsertPoint(there);
  llvm::Value* next = highHalf(b, fact, loop, nextWord);
  llvm::BasicBlock* list = newBlock(f, "pipe.list");
  llvm::BasicBlock* none = b.GetInsertBlock();
  b.CreateCondBr(b.CreateICmpEQ(next, b.getInt32(MELD_NATIVE_NO_FACT)), done, list);
  b.SetInsertPoint(list);
  llvm::Value* cell =
      b.CreateLoad(b.getInt64Ty(), factWord(b, loop, next, b.CreateAdd(loop.argOffset, b.getInt64(field))));
  b.CreateBr(done);
  b.SetInsertPoint(done);
  llvm::PHINode* nextPhi = b.CreatePHI(b.getInt32Ty(), 3);
  nextPhi->addIncoming(b.getInt32(MELD_NATIVE_NO_FACT), from);
  nextPhi->addIncoming(b.getInt32(MELD_NATIVE_NO_FACT), none);
  nextPhi->addIncoming(next, list);
  llvm::PHINode* cellPhi = b.CreatePHI(b.getInt64Ty(), 3);
  cellPhi->addIncoming(b.getInt64(0), from);
  cellPhi->addIncoming(b.getInt64(0), none);
  cellPhi->addIncoming(cell, list);
  return {nextPhi, cellPhi};
}

void RegionLowering::fetchCell(llvm::IRBuilder<>& b, const ListPipe& pipe, int k, llvm::Value* cell) {
  b.CreateStore(cell, b.CreateConstInBoundsGEP2_32(pipe.cellsType, pipe.cells, 0, unsigned(k - 1)));
  // read, high locality, data (a prefetch of address 0 is harmless)
  b.CreateIntrinsic(llvm::Intrinsic::prefetch, {b.getPtrTy()},
                    {b.CreateIntToPtr(cell, b.getPtrTy()), b.getInt32(0), b.getInt32(3), b.getInt32(1)});
}

RegionLowering::ListPipe RegionLowering::startListPipeline(Function& f, llvm::IRBuilder<>& b,
                                                           const LoopView& loop, llvm::Value* first,
                                                           llvm::Value* nextWord, std::uint32_t field) {
  ListPipe pipe;
  pipe.cellsType = llvm::ArrayType::get(b.getInt64Ty(), kListPipelineFacts);
  pipe.cells = local(f, pipe.cellsType, "pipe.cells");
  pipe.ahead = local(f, b.getInt32Ty(), "pipe.ahead");
  llvm::Value* ahead = first;
  for (int k = 1; k <= kListPipelineFacts; ++k) {
    auto [next, cell] = nextWithList(f, b, loop, ahead, nextWord, field);
    ahead = next;
    for (int d = listPipelineDepth(k); d > 0; --d) cell = tailOrNull(f, b, cell);
    fetchCell(b, pipe, k, cell);
  }
  b.CreateStore(ahead, pipe.ahead);
  return pipe;
}

void RegionLowering::stepListPipeline(Function& f, llvm::IRBuilder<>& b, const LoopView& loop,
                                      const ListPipe& pipe, llvm::Value* nextWord, std::uint32_t field) {
  for (int k = 1; k < kListPipelineFacts; ++k) {  // the fact k + 1 on is now k on
    llvm::Value* cell = b.CreateLoad(
        b.getInt64Ty(), b.CreateConstInBoundsGEP2_32(pipe.cellsType, pipe.cells, 0, unsigned(k)));
    if (listPipelineDepth(k) != listPipelineDepth(k + 1))  // one cell deeper
      fetchCell(b, pipe, k, tailOrNull(f, b, cell));
    else
      b.CreateStore(cell, b.CreateConstInBoundsGEP2_32(pipe.cellsType, pipe.cells, 0, unsigned(k - 1)));
  }
  auto [next, cell] = nextWithList(f, b, loop, b.CreateLoad(b.getInt32Ty(), pipe.ahead), nextWord, field);
  b.CreateStore(next, pipe.ahead);
  fetchCell(b, pipe, kListPipelineFacts, cell);
}

}  // namespace meldc::native::detail
