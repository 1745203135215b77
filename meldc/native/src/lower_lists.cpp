// The fact store's list primitives in native code (FactTable's connect, moveToBack and the links
// of fill), for the code that writes plain tables itself: UPDATE (lower_writes.cpp) and the end of
// a rule run (lower_rule_end.cpp).
#include "region_lowering.hpp"

namespace meldc::native::detail {

RegionLowering::TableWords RegionLowering::tableWords(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred) {
  TableWords t{b, t_.tableType, tableOf(f, b, pred)};
  t.words = b.CreateLoad(b.getPtrTy(), t.field(kTableWords, b.getPtrTy()));
  t.stride = b.CreateZExt(t.field(kTableStride, b.getInt32Ty()), b.getInt64Ty());
  return t;
}

void RegionLowering::setHalf(llvm::IRBuilder<>& b, llvm::Value* word, llvm::Value* v, bool high) {
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Value* kept =
      b.CreateAnd(b.CreateLoad(i64, word), b.getInt64(high ? 0xFFFFFFFFull : 0xFFFFFFFF00000000ull));
  llvm::Value* v64 = b.CreateZExt(v, i64);
  b.CreateStore(b.CreateOr(kept, high ? b.CreateShl(v64, 32) : v64), word);
}

// One end of connect: the list head's word if `at` is MELD_NATIVE_NO_FACT, else at's link.
void RegionLowering::connectEnd(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                                const TableWords& t, llvm::Value* at, HeadWord headWord, llvm::Value* other) {
  llvm::BasicBlock* atHead = newBlock(f, "connect.head");
  llvm::BasicBlock* inside = newBlock(f, "connect.inside");
  llvm::BasicBlock* linked = newBlock(f, "connect.linked");
  b.CreateCondBr(b.CreateICmpEQ(at, b.getInt32(MELD_NATIVE_NO_FACT)), atHead, inside);
  b.SetInsertPoint(atHead);
  b.CreateStore(other, listHead(f, b, heads, pred, headWord));
  b.CreateBr(linked);
  b.SetInsertPoint(inside);
  setHalf(b, t.word0(at), other, headWord == kHeadFirst);  // p's next, or nx's previous
  b.CreateBr(linked);
  b.SetInsertPoint(linked);
}

void RegionLowering::connect(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                             const TableWords& t, llvm::Value* p, llvm::Value* nx) {
  connectEnd(f, b, heads, pred, t, p, kHeadFirst, nx);
  connectEnd(f, b, heads, pred, t, nx, kHeadLast, p);
}

void RegionLowering::moveToBack(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                                const TableWords& t, llvm::Value* fact) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Value* last = b.CreateLoad(i32, listHead(f, b, heads, pred, kHeadLast));
  llvm::BasicBlock* move = newBlock(f, "move");
  llvm::BasicBlock* done = newBlock(f, "moved");
  b.CreateCondBr(b.CreateICmpEQ(last, fact), done, move);
  b.SetInsertPoint(move);
  llvm::Value* links = b.CreateLoad(b.getInt64Ty(), t.word0(fact));
  connect(f, b, heads, pred, t, b.CreateTrunc(links, i32), b.CreateTrunc(b.CreateLShr(links, 32), i32));
  linkLast(f, b, heads, pred, t, fact);  // (the list's last fact is still `last`)
  b.CreateBr(done);
  b.SetInsertPoint(done);
}

void RegionLowering::linkLast(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                              const TableWords& t, llvm::Value* fact) {
  // connect(last, fact) and connect(fact, none), with the fact's own links written at once.
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Value* lastAt = listHead(f, b, heads, pred, kHeadLast);
  llvm::Value* last = b.CreateLoad(b.getInt32Ty(), lastAt);
  connectEnd(f, b, heads, pred, t, last, kHeadFirst, fact);
  b.CreateStore(b.CreateOr(b.CreateZExt(last, i64), b.getInt64(std::uint64_t(MELD_NATIVE_NO_FACT) << 32)),
                t.word0(fact));
  b.CreateStore(fact, lastAt);
}

}  // namespace meldc::native::detail
