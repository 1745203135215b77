// Bytecode to LLVM IR, one lowering per opcode (the switch in lowerInstruction lists every opcode of
// opcodes.def: -Wswitch says when one is missing).
//
// A code block becomes one function per place the interpreter's exec() is entered: the block's
// start, and the body of each of its loops (called once per fact by the native loop, or by the VM's
// loop helper for ITER_SORTED). Each function returns what exec() returns there (native_abi.h).
// Inside a function every instruction is a basic block; jumps are branches, arithmetic on unboxed
// registers is inline, loops, LOAD/TEST runs, FIRE and built-in calls are native (lower_facts.cpp),
// and the other instructions call the VM's helper that runs the interpreter's own code for them.
#include <algorithm>

#include "region_lowering.hpp"

namespace meldc::native {
namespace detail {

llvm::Function* RegionLowering::region(std::uint32_t start, const std::set<std::uint32_t>& bound,
                                       bool nativeBody) {
  if (auto it = regions_.find(start); it != regions_.end()) return it->second;
  const bool entry = start == 0 && !wrapsEntry_;
  auto* fn = llvm::Function::Create(nativeBody ? t_.bodyType : t_.blockType,
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

void RegionLowering::lowerRegion(Function& f, std::uint32_t start, bool nativeBody) {
  f.entry = newBlock(f, "entry");
  llvm::IRBuilder<> b(f.entry);
  auto arg = f.fn->arg_begin();
  f.helpers = &*arg++;
  f.vm = &*arg++;
  f.frame = &*arg++;
  f.regs = &*arg++;
  // A body that native code loops over shares its caller's loops' array (and the queens_violation
  // masks after it); the block's start and a body the VM's loop helper calls have their own.
  f.loops = nativeBody ? static_cast<llvm::Value*>(&*arg)
                       : b.CreateAlloca(b.getPtrTy(),
                                        b.getInt32(std::max<std::uint32_t>(block_.slots + queensWords_, 1)),
                                        "loops");
  if (!nativeBody) forgetAllQueensRows(f, b);
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

void RegionLowering::lowerInstruction(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  const std::uint32_t* c = code_.data() + pc;
  const std::uint32_t next = pc + length(pc);
  // (A run of LOADs forgets the masks of the registers it writes itself: lowerSlotRun.)
  if (!queensSites_.empty() && Opcode(c[0]) != Opcode::LOAD && Opcode(c[0]) != Opcode::TEST)
    forgetQueensRows(f, b, meldvm::detail::writtenRegister(code_, pc));
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
    case Opcode::DERIVE:
    case Opcode::SEND:
    case Opcode::UPDATE:
      return lowerFactOut(f, b, pc);
    case Opcode::RET:
      return ret(b, kReturn);
    case Opcode::RET_IF_UPDATED: {
      llvm::Value* updated = b.CreateCall(t_.updatedType, helper(f, b, kUpdated), {f.frame});
      llvm::BasicBlock* stop = newBlock(f, "updated");
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
    case Opcode::HOST: {  // Value::fromNode(host): every rule's first instruction
      llvm::Value* host =
          b.CreateLoad(b.getInt32Ty(), b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameHost));
      b.CreateStore(b.CreateZExt(host, b.getInt64Ty()), reg(f, b, c[1]));
      return (void)b.CreateBr(at(f, next));
    }
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
    case Opcode::GLOBAL:  // an unboxed value is its word, read at each GLOBAL (SETGLOBAL may change it)
      if (!boxed(c[1])) {
        llvm::Value* globals = contextField(f, b, kContextGlobals, b.getPtrTy());
        llvm::Value* word = b.CreateConstInBoundsGEP1_64(b.getInt64Ty(), globals, c[2]);
        b.CreateStore(b.CreateLoad(b.getInt64Ty(), word), reg(f, b, c[1]));
        return (void)b.CreateBr(at(f, next));
      }
      return step(f, b, pc);  // a boxed one is retained: the interpreter's case
    case Opcode::EQ:  // ints, booleans, nodes, threads: their bits (the interpreter's valuesEqualFast)
    case Opcode::NE:
      if (bitsAreIdentity(c[4])) {
        llvm::Value* same = b.CreateICmpEQ(loadReg(f, b, c[2]), loadReg(f, b, c[3]));
        storeBool(f, b, c[1], Opcode(c[0]) == Opcode::EQ ? same : b.CreateNot(same));
        return (void)b.CreateBr(at(f, next));
      }
      return step(f, b, pc);  // the others by content
    case Opcode::LOAD:
      return lowerSlotRun(f, b, pc);
    case Opcode::CALL:
      return lowerCall(f, b, pc);
    case Opcode::CONS:
      return lowerCons(f, b, pc);
    // ---- the interpreter's code, through the step helper: the fact store, the heap (boxed
    // registers own references), messages, the scheduler, errors ----
    case Opcode::MOV:
    case Opcode::MOVS:
    case Opcode::NIL:
    case Opcode::SETGLOBAL:
    case Opcode::WORLD:
    case Opcode::CPUS:
    case Opcode::THREAD:
    case Opcode::ARG:
    case Opcode::DIVI:  // throws on a zero divisor
    case Opcode::MODI:
    case Opcode::HEAD:
    case Opcode::TAIL:
    case Opcode::STRUCT:
    case Opcode::FIELD:
    case Opcode::CALLF:
    case Opcode::CALLX:
    case Opcode::SEND_DELAY:
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
    case Opcode::AXIOM_FACTS:  // axiom blocks are interpreted; kept total all the same
      return step(f, b, pc);
    case Opcode::Count:
      break;
  }
  throw NativeError("block '" + block_.label + "': no lowering for opcode " + std::to_string(c[0]));
}

}  // namespace detail

using detail::RegionLowering;

llvm::FunctionType* blockFunctionType(llvm::LLVMContext& context) {
  llvm::PointerType* ptr = llvm::PointerType::getUnqual(context);
  return llvm::FunctionType::get(llvm::Type::getInt32Ty(context), {ptr, ptr, ptr, ptr}, false);
}

NativeTypes::NativeTypes(llvm::Module& m) : module(m), context(m.getContext()) {
  llvm::Type* ptr = llvm::PointerType::getUnqual(context);
  llvm::Type* i8 = llvm::Type::getInt8Ty(context);
  llvm::Type* i32 = llvm::Type::getInt32Ty(context);
  llvm::Type* voidTy = llvm::Type::getVoidTy(context);
  llvm::Type* i64 = llvm::Type::getInt64Ty(context);
  helpersType = llvm::StructType::create(
      context, {i32, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr, ptr}, "meld_native_helpers");
  loopStructType =
      llvm::StructType::create(context, {ptr, ptr, ptr, ptr, i32, i32, i32, i32}, "meld_native_loop");
  slotType = llvm::StructType::create(context, {i32, i32, i32, i32, ptr}, "meld_native_slot");
  // Pointers up to heads_per_node, then heads_per_node and rule_words (region_lowering.hpp checks
  // the C struct's offsets against the same enum).
  std::vector<llvm::Type*> contextFields(detail::kContextHeadsPerNode, ptr);
  contextFields.insert(contextFields.end(), {i32, i32});
  contextType = llvm::StructType::create(context, contextFields, "meld_native_context");
  consumedType = llvm::StructType::create(context, {ptr, i32, i32}, "meld_native_consumed");
  arrayType = llvm::StructType::create(context, {ptr, i32, i32}, "meld_native_array");
  heapType = llvm::StructType::create(context, {ptr, ptr, ptr, ptr, ptr}, "meld_native_heap");
  tableType =
      llvm::StructType::create(context, {ptr, i32, i32, i32, i32, ptr, ptr, ptr}, "meld_native_table");
  fieldIndexType = llvm::StructType::create(context, {ptr, ptr, ptr, i32, i32}, "meld_native_field_index");
  frameHeadType = llvm::StructType::create(context, {ptr, ptr, ptr, ptr, ptr, ptr, i32, i8, i8},
                                           "meld_native_frame_head");
  loopBeginType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32, ptr}, false);
  blockType = blockFunctionType(context);
  bodyType = llvm::FunctionType::get(i32, {ptr, ptr, ptr, ptr, ptr}, false);
  builtinType = llvm::FunctionType::get(i64, {ptr, ptr, i32, i32}, false);
  loopType = llvm::FunctionType::get(i32, {ptr, ptr, ptr, i32, ptr}, false);
  stepType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32}, false);
  testType = llvm::FunctionType::get(i32, {ptr, ptr, i32}, false);
  consumeType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32}, false);
  updatedType = llvm::FunctionType::get(i32, {ptr}, false);
  slotArgsType = llvm::FunctionType::get(ptr, {ptr, ptr, i32}, false);
  releaseLastType = llvm::FunctionType::get(voidTy, {ptr, i32, i64}, false);
  deriveType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32, i32, ptr}, false);
  sendType = llvm::FunctionType::get(voidTy, {ptr, ptr, i32, i32, i32, ptr}, false);
}

llvm::Function* lowerBlock(NativeTypes& types, const meldvm::Program& program, const meldvm::CodeBlock& block,
                           const std::string& name, BlockKind kind) {
  return RegionLowering(types, program, block, name, kind).entry();
}

}  // namespace meldc::native
