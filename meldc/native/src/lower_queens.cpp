// queens_violation(Y, L), the built-in of n-queens, inline (region_lowering.hpp says what each
// function does).
//
// n-queens asks it for every cell of the next column, with the same list of the queens placed so
// far: `partial(A, L) -o {B, Y | !next(A, B, Y), ~queens_violation(Y, L) | ...}`. Each call walked
// L again, one cell after the other (each load waits for the one before), and those walks were
// half of the native run of n-queens 13. Where a loop around the call keeps L's register
// (outermostLoopKeeping), the rows L rules out are gathered in one walk into a 64-bit mask, kept
// beside the loops' array until the register is written again, and each call tests one bit.
#include "region_lowering.hpp"

namespace meldc::native::detail {

namespace {
// Lists at least this long keep the walk: the distances must stay far from overflowing an int
// for the mask to mean what the walk computes (rows ± distance wrap around in the interpreter).
constexpr std::uint64_t kLongestMaskedList = std::uint64_t(1) << 30;
}  // namespace

void RegionLowering::planQueensSites() {
  std::uint32_t words = 0;
  meldvm::detail::forEachInstruction(code_, [&](std::size_t pc) {
    if (Opcode(code_[pc]) != Opcode::CALL || code_[pc + 2] != queensId_ || code_[pc + 4] != 2) return;
    const std::uint32_t list = code_[pc + 6];
    if (meldvm::detail::outermostLoopKeeping(code_, pc, list) < 0) return;  // computed once per call
    queensSites_[std::uint32_t(pc)] = {block_.slots + words, list};
    words += 2;
  });
  queensWords_ = words;
}

void RegionLowering::forgetQueensRows(Function& f, llvm::IRBuilder<>& b, std::int64_t written) {
  if (written < 0) return;
  for (const auto& [pc, site] : queensSites_)
    if (site.listReg == std::uint64_t(written))
      b.CreateStore(b.getInt64(kRowsUnknown), queensWord(f, b, site, 0));
}

void RegionLowering::forgetAllQueensRows(Function& f, llvm::IRBuilder<>& b) {
  for (const auto& [pc, site] : queensSites_)
    b.CreateStore(b.getInt64(kRowsUnknown), queensWord(f, b, site, 0));
}

RegionLowering::CellWalk RegionLowering::beginCellWalk(Function& f, llvm::IRBuilder<>& b, llvm::Value* list,
                                                       llvm::Type* distanceType, const std::string& name) {
  llvm::BasicBlock* from = b.GetInsertBlock();
  CellWalk w{newBlock(f, name + ".walk"), nullptr, nullptr};
  b.CreateBr(w.head);
  b.SetInsertPoint(w.head);
  w.at = b.CreatePHI(b.getInt64Ty(), 2, name + ".list");
  w.distance = b.CreatePHI(distanceType, 2, name + ".d");
  w.at->addIncoming(list, from);
  w.distance->addIncoming(llvm::ConstantInt::get(distanceType, 1), from);
  return w;
}

void RegionLowering::stepCellWalk(llvm::IRBuilder<>& b, const CellWalk& w) {
  llvm::BasicBlock* here = b.GetInsertBlock();
  w.at->addIncoming(cellWord(b, w.at, MELD_NATIVE_LIST_TAIL_WORD), here);
  w.distance->addIncoming(b.CreateAdd(w.distance, llvm::ConstantInt::get(w.distance->getType(), 1)), here);
  b.CreateBr(w.head);
}

std::pair<llvm::Value*, llvm::Value*> RegionLowering::queensRows(Function& f, llvm::IRBuilder<>& b,
                                                                 llvm::Value* list) {
  llvm::Type* i64 = b.getInt64Ty();
  llvm::BasicBlock* from = b.GetInsertBlock();
  const CellWalk w = beginCellWalk(f, b, list, i64, "rows");
  llvm::PHINode* mask = b.CreatePHI(i64, 2, "rows.mask");
  mask->addIncoming(b.getInt64(0), from);
  llvm::BasicBlock* more = newBlock(f, "rows.more");
  llvm::BasicBlock* cell = newBlock(f, "rows.cell");
  llvm::BasicBlock* done = newBlock(f, "rows.done");
  b.CreateCondBr(b.CreateICmpEQ(w.at, b.getInt64(0)), done, more);
  b.SetInsertPoint(more);
  b.CreateCondBr(b.CreateICmpUGE(w.distance, b.getInt64(kLongestMaskedList)), done, cell);
  b.SetInsertPoint(cell);
  llvm::Value* queen =
      b.CreateSExt(b.CreateTrunc(cellWord(b, w.at, MELD_NATIVE_LIST_HEAD_WORD), b.getInt32Ty()), i64);
  // A queen in row q at distance d rules out rows q, q - d and q + d of the next column (those
  // in [0, 64) are the mask's bits).
  llvm::Value* rows = mask;
  for (llvm::Value* row : {queen, b.CreateSub(queen, w.distance), b.CreateAdd(queen, w.distance)}) {
    llvm::Value* bit = b.CreateShl(b.getInt64(1), b.CreateAnd(row, b.getInt64(63)));
    rows = b.CreateOr(rows, b.CreateSelect(b.CreateICmpULT(row, b.getInt64(64)), bit, b.getInt64(0)));
  }
  mask->addIncoming(rows, cell);
  stepCellWalk(b, w);
  b.SetInsertPoint(done);
  llvm::PHINode* known = b.CreatePHI(b.getInt1Ty(), 2, "rows.known");
  known->addIncoming(b.getTrue(), w.head);
  known->addIncoming(b.getFalse(), more);
  return {mask, known};
}

llvm::Value* RegionLowering::cachedQueensViolation(Function& f, llvm::IRBuilder<>& b, const QueensSite& site,
                                                   llvm::Value* row, llvm::Value* list) {
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Value* stateWord = queensWord(f, b, site, 0);
  llvm::Value* maskWord = queensWord(f, b, site, 1);
  llvm::BasicBlock* gather = newBlock(f, "rows.gather");
  llvm::BasicBlock* ready = newBlock(f, "rows.ready");
  llvm::BasicBlock* masked = newBlock(f, "rows.masked");
  llvm::BasicBlock* walk = newBlock(f, "rows.fallback");
  llvm::BasicBlock* done = newBlock(f, "rows.answer");
  b.CreateCondBr(b.CreateICmpEQ(b.CreateLoad(i64, stateWord), b.getInt64(kRowsUnknown)), gather, ready);
  b.SetInsertPoint(gather);
  const auto [mask, known] = queensRows(f, b, list);
  b.CreateStore(mask, maskWord);
  b.CreateStore(b.CreateSelect(known, b.getInt64(kRowsMasked), b.getInt64(kRowsWalked)), stateWord);
  b.CreateBr(ready);
  b.SetInsertPoint(ready);
  llvm::Value* usable = b.CreateAnd(b.CreateICmpEQ(b.CreateLoad(i64, stateWord), b.getInt64(kRowsMasked)),
                                    b.CreateICmpULT(row, b.getInt32(64)));
  b.CreateCondBr(usable, masked, walk);
  b.SetInsertPoint(masked);
  llvm::Value* bit =
      b.CreateAnd(b.CreateLShr(b.CreateLoad(i64, maskWord), b.CreateZExt(row, i64)), b.getInt64(1));
  llvm::Value* fromMask = b.CreateICmpNE(bit, b.getInt64(0));
  b.CreateBr(done);
  b.SetInsertPoint(walk);
  llvm::Value* fromWalk = queensViolation(f, b, row, list);
  llvm::BasicBlock* walked = b.GetInsertBlock();
  b.CreateBr(done);
  b.SetInsertPoint(done);
  llvm::PHINode* result = b.CreatePHI(b.getInt1Ty(), 2, "queens.conflict");
  result->addIncoming(fromMask, masked);
  result->addIncoming(fromWalk, walked);
  return result;
}

// builtins_lists.cpp's queens_violation, inline: the queens of the list (nearest column first)
// against a new one in `row` (i32), true if one shares its row or a diagonal. n-queens calls it
// for every cell of the next column: through the builtins table it was a fifth of the native run
// (the span of arguments, the call, the walk behind an opaque call).
llvm::Value* RegionLowering::queensViolation(Function& f, llvm::IRBuilder<>& b, llvm::Value* row,
                                             llvm::Value* list) {
  const CellWalk w = beginCellWalk(f, b, list, b.getInt32Ty(), "queens");
  llvm::BasicBlock* cell = newBlock(f, "queens.cell");
  llvm::BasicBlock* next = newBlock(f, "queens.next");
  llvm::BasicBlock* done = newBlock(f, "queens.done");
  b.CreateCondBr(b.CreateICmpEQ(w.at, b.getInt64(0)), done, cell);  // the empty list: no conflict
  b.SetInsertPoint(cell);
  llvm::Value* queen = b.CreateTrunc(cellWord(b, w.at, MELD_NATIVE_LIST_HEAD_WORD), b.getInt32Ty());
  // Wrapping sums, as the interpreter's intAdd and intSub.
  llvm::Value* conflict =
      b.CreateOr(b.CreateICmpEQ(queen, row), b.CreateOr(b.CreateICmpEQ(queen, b.CreateAdd(row, w.distance)),
                                                        b.CreateICmpEQ(queen, b.CreateSub(row, w.distance))));
  b.CreateCondBr(conflict, done, next);
  b.SetInsertPoint(next);
  stepCellWalk(b, w);
  b.SetInsertPoint(done);
  llvm::PHINode* result = b.CreatePHI(b.getInt1Ty(), 2, "queens.conflict");
  result->addIncoming(b.getFalse(), w.head);
  result->addIncoming(b.getTrue(), cell);
  return result;
}

}  // namespace meldc::native::detail
