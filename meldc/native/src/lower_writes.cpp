// UPDATE, SEND and DERIVE in native code, without the VM when meld_native_context allows it.
// UPDATE: the fact changed in place and the rules over its predicate made candidates again;
// through the update helper it cost heat-transfer about 200 instructions per update, most of them
// in finding again what the block already knows (the table, the list, the rules to wake). SEND and
// DERIVE: the fact appended to the run's sent or derived facts, as Machine::send's and derive's
// common case does; a persistent fact sent (or retracted: shortest-path sends both) to the node
// run's persistent sent facts, as Machine::sendAny does (through the send helper, Machine::send
// and sendAny it cost shortest-path 130 instructions a message more: 2.06 G -> 1.77 G natively for
// 20,000 nodes, before postAll fetched the mailbox entries that sendAny used to fetch).
#include <llvm/IR/MDBuilder.h>

#include <algorithm>

#include "region_lowering.hpp"

namespace meldc::native::detail {

std::optional<std::vector<RegionLowering::RuleTrigger>> RegionLowering::triggersOf(std::uint32_t pred) const {
  std::vector<RuleTrigger> triggers;
  for (std::uint32_t r = 0; r < program_.rules.size(); ++r) {
    const std::vector<meldvm::PredId>& body = program_.rules[r].bodyPredicates;
    if (std::find(body.begin(), body.end(), pred) == body.end()) continue;
    RuleTrigger t{r, {}};
    for (meldvm::PredId q : body) {
      if (program_.predicates[q].thread) return std::nullopt;  // the VM looks at the thread's node
      if (q != pred && std::find(t.needs.begin(), t.needs.end(), q) == t.needs.end()) t.needs.push_back(q);
    }
    triggers.push_back(std::move(t));
  }
  return triggers;
}

void RegionLowering::lowerUpdate(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  const std::uint32_t* c = code_.data() + pc;
  const std::uint32_t s = c[1], count = c[3];
  const bool toBack = (c[2] & meldvm::kUpdateMoveToBack) != 0;
  llvm::Value* args = gatherArgs(f, b, c + 4, count);
  llvm::BasicBlock* next = at(f, pc + length(pc));
  auto callVm = [&] {
    b.CreateCall(t_.sendType, helper(f, b, kUpdate),
                 {f.vm, f.frame, b.getInt32(pc), b.getInt32(s), b.getInt32(toBack), args});
    b.CreateBr(next);
  };
  const std::int64_t pred = slotPredicate(s);
  const auto triggers = pred >= 0 ? triggersOf(std::uint32_t(pred)) : std::nullopt;
  if (!triggers) return callVm();

  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* slots = b.CreateLoad(ptr, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameSlots));
  llvm::Value* host = b.CreateLoad(i32, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameHost));
  llvm::Value* node = b.CreateLoad(i32, slotField(b, slots, s, kSlotNode));
  llvm::Value* fact = b.CreateLoad(i32, slotField(b, slots, s, kSlotFact));
  // (A predicate with no index declared nor looked up never has a KEYED table: no check then.)
  const bool indexed = indexedLinear().count(std::uint32_t(pred)) != 0;
  llvm::Value* conditions[] = {writesHere(f, b, std::uint32_t(pred),
                                          MELD_NATIVE_TABLE_PLAIN | (indexed ? MELD_NATIVE_TABLE_KEYED : 0u)),
                               b.CreateICmpEQ(node, host)};
  hereOrVm(f, b, conditions, "update", callVm);
  const TableWords table = tableWords(f, b, std::uint32_t(pred));
  if (indexed) keysKeptOrVm(f, b, table, fact, args, count, toBack, callVm);
  llvm::Value* heads = nodeHeads(f, b, host);
  if (toBack) moveToBack(f, b, heads, std::uint32_t(pred), table, fact);
  llvm::Value* argsAt =
      b.CreateInBoundsGEP(i64, table.word0(fact), b.CreateZExt(table.field(kTableArgOffset, i32), i64));
  llvm::Type* argsType = llvm::ArrayType::get(i64, std::max<std::uint32_t>(count, 1));
  for (std::uint32_t i = 0; i < count; ++i)
    b.CreateStore(b.CreateLoad(i64, b.CreateConstInBoundsGEP2_32(argsType, args, 0, i)),
                  b.CreateConstInBoundsGEP1_64(i64, argsAt, i));
  wakeRules(f, b, heads, host, *triggers);
  increment(b, contextField(f, b, kContextFactsDerived, ptr));
  increment(b, contextField(f, b, kContextRunDerived, ptr));
  b.CreateStore(b.getInt8(1), b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameUpdated));
  b.CreateBr(next);
}

void RegionLowering::lowerSend(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  const std::uint32_t* c = code_.data() + pc;
  const std::uint32_t pred = c[1], count = c[3];
  llvm::Type* i8 = b.getInt8Ty();
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* dest = loadInt(f, b, c[2]);  // the node is the register's low half (Value::asNode)
  llvm::Value* args = gatherArgs(f, b, c + 4, count);
  llvm::BasicBlock* next = at(f, pc + length(pc));
  auto viaVm = [&] {
    b.CreateCall(t_.sendType, helper(f, b, kSend),
                 {f.vm, f.frame, b.getInt32(pc), b.getInt32(pred), dest, args});
  };
  const meldvm::PredicateDesc& d = program_.predicates[pred];
  // Run or stored elsewhere; or a persistent fact that holds references, which the persistent
  // sent buffer never takes (MELD_NATIVE_TABLE_PERSISTENT_SENT): the VM's.
  if (d.action || d.thread || (!d.linear && !boxedFields(pred).empty())) {
    viaVm();
    return (void)b.CreateBr(next);
  }
  llvm::Value* more = b.CreateAnd(
      b.CreateICmpNE(b.CreateLoad(i8, contextField(f, b, kContextSendsBuffered, ptr)), b.getInt8(0)),
      b.CreateICmpULT(dest, b.CreateLoad(i32, contextField(f, b, kContextLiveBelow, ptr))));
  // A persistent fact (or its retraction) waits for the node run's end in its own buffer: the VM
  // posts those before the linear ones (Machine::flushOutgoing).
  const Buffer buffer =
      d.linear ? Buffer{kContextSent, kContextSentArgs}
               : Buffer{kContextSentPersistent, kContextSentArgs, MELD_NATIVE_TABLE_PERSISTENT_SENT, true};
  appendFact(f, b, buffer, dest, pred, args, count, more, next, viaVm);
  increment(b, contextField(f, b, kContextFactsSent, ptr));
  // A linear fact's receiver's list head is written when the run ends: fetched now, as
  // Machine::send does.
  if (d.linear)
    b.CreateIntrinsic(llvm::Intrinsic::prefetch, {ptr},
                      {listHead(f, b, nodeHeads(f, b, dest), pred, kHeadFirst), b.getInt32(1), b.getInt32(3),
                       b.getInt32(1)});
  b.CreateBr(next);
}

void RegionLowering::lowerDerive(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {
  const std::uint32_t* c = code_.data() + pc;
  const std::uint32_t pred = c[1], count = c[2];
  llvm::Value* args = gatherArgs(f, b, c + 3, count);
  llvm::BasicBlock* next = at(f, pc + length(pc));
  auto viaVm = [&] {
    b.CreateCall(t_.deriveType, helper(f, b, kDerive),
                 {f.vm, f.frame, b.getInt32(pc), b.getInt32(pred), args});
  };
  const meldvm::PredicateDesc& d = program_.predicates[pred];
  if (!d.linear || d.action || d.thread) {  // persistent facts, actions and thread facts: the VM's
    viaVm();
    return (void)b.CreateBr(next);
  }
  llvm::Value* host = b.CreateLoad(b.getInt32Ty(), b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameHost));
  appendFact(f, b, {kContextDerived, kContextDerivedArgs}, host, pred, args, count, b.getTrue(), next, viaVm);
  b.CreateBr(next);
}

void RegionLowering::appendFact(Function& f, llvm::IRBuilder<>& b, Buffer buffer, llvm::Value* node,
                                std::uint32_t pred, llvm::Value* args, std::uint32_t count, llvm::Value* more,
                                llvm::BasicBlock* next, const std::function<void()>& viaVm) {
  llvm::Type* i8 = b.getInt8Ty();
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* facts = contextField(f, b, buffer.facts, ptr);
  llvm::Value* words = contextField(f, b, buffer.args, ptr);
  auto arrayField = [&](llvm::Value* array, unsigned k) { return b.CreateStructGEP(t_.arrayType, array, k); };
  llvm::Value* size = b.CreateLoad(i32, arrayField(facts, 1));
  llvm::Value* wordsSize = b.CreateLoad(i32, arrayField(words, 1));
  // A fact that carries lists, strings or structs: the buffer's copy holds a reference to each,
  // retained here (MELD_NATIVE_TABLE_BUFFERED_BOXED). Through the send helper, n-queens 10 took
  // 134 instructions a placement sent, and 8queens-12 sends and derives nothing else.
  const std::vector<std::uint32_t> boxedArgs = boxedFields(pred);
  const std::uint32_t flag = boxedArgs.empty() ? buffer.flag : MELD_NATIVE_TABLE_BUFFERED_BOXED;
  llvm::Value* conditions[] = {
      more, writesHere(f, b, pred, flag, buffer.withSign),
      b.CreateICmpULT(size, b.CreateLoad(i32, arrayField(facts, 2))),
      b.CreateICmpULE(b.CreateAdd(wordsSize, b.getInt32(count)), b.CreateLoad(i32, arrayField(words, 2)))};
  hereOrVm(f, b, conditions, "append", [&] {
    viaVm();
    b.CreateBr(next);
  });
  llvm::Value* entry =
      b.CreateInBoundsGEP(i8, b.CreateLoad(ptr, arrayField(facts, 0)),
                          b.CreateMul(b.CreateZExt(size, i64), b.getInt64(sizeof(meld_native_sent_fact))));
  auto field = [&](SentFactByte k) { return b.CreateConstInBoundsGEP1_64(i8, entry, k); };
  b.CreateStore(node, field(kSentNode));
  b.CreateStore(b.getInt32(pred), field(kSentPred));
  llvm::Value* negative = b.getInt8(0);
  if (buffer.withSign)
    negative = b.CreateLoad(i8, b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameNegative));
  b.CreateStore(negative, field(kSentNegative));
  b.CreateStore(wordsSize, field(kSentArgs));
  b.CreateStore(b.getInt32(0), field(kSentDelay));
  b.CreateStore(b.getInt8(0), field(kSentCancelled));
  llvm::Value* argsAt =
      b.CreateInBoundsGEP(i64, b.CreateLoad(ptr, arrayField(words, 0)), b.CreateZExt(wordsSize, i64));
  llvm::Type* argsType = llvm::ArrayType::get(i64, std::max<std::uint32_t>(count, 1));
  for (std::uint32_t i = 0; i < count; ++i)
    b.CreateStore(b.CreateLoad(i64, b.CreateConstInBoundsGEP2_32(argsType, args, 0, i)),
                  b.CreateConstInBoundsGEP1_64(i64, argsAt, i));
  for (std::uint32_t i : boxedArgs)
    adjustCount(f, b, b.CreateLoad(i64, b.CreateConstInBoundsGEP2_32(argsType, args, 0, i)), true,
                program_.predicates[pred].fields[i]);
  b.CreateStore(b.CreateAdd(size, b.getInt32(1)), arrayField(facts, 1));
  b.CreateStore(b.CreateAdd(wordsSize, b.getInt32(count)), arrayField(words, 1));
  // A retraction derives nothing (Machine::sendAny).
  llvm::Value* derived = b.CreateZExt(b.CreateICmpEQ(negative, b.getInt8(0)), i64);
  for (ContextField counter : {kContextFactsDerived, kContextRunDerived}) {
    llvm::Value* at = contextField(f, b, counter, ptr);
    b.CreateStore(b.CreateAdd(b.CreateLoad(i64, at), derived), at);
  }
}

llvm::Value* RegionLowering::writesHere(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred,
                                        std::uint32_t flag, bool anySign) {
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* flags = b.CreateLoad(i32, b.CreateStructGEP(t_.tableType, tableOf(f, b, pred), kTableFlags));
  llvm::Value* here =
      b.CreateAnd(b.CreateICmpNE(b.CreateAnd(flags, b.getInt32(flag)), b.getInt32(0)),
                  b.CreateIsNull(b.CreateLoad(ptr, contextField(f, b, kContextDerivations, ptr))));
  if (anySign) return here;
  llvm::Value* negative =
      b.CreateLoad(b.getInt8Ty(), b.CreateStructGEP(t_.frameHeadType, f.frame, kFrameNegative));
  return b.CreateAnd(here, b.CreateICmpEQ(negative, b.getInt8(0)));
}

void RegionLowering::hereOrVm(Function& f, llvm::IRBuilder<>& b, std::span<llvm::Value* const> conditions,
                              const std::string& name, const std::function<void()>& viaVm) {
  llvm::Value* here = b.getTrue();
  for (llvm::Value* c : conditions) here = b.CreateAnd(here, c);
  llvm::BasicBlock* native = newBlock(f, name);
  llvm::BasicBlock* vm = newBlock(f, name + ".vm");
  b.CreateCondBr(here, native, vm, llvm::MDBuilder(t_.context).createBranchWeights(1 << 10, 1));
  b.SetInsertPoint(vm);
  viaVm();
  b.SetInsertPoint(native);
}

// Machine::factAdded for a fact of the host: each rule over the predicate becomes a candidate if
// the host has a fact of every predicate of its body.
void RegionLowering::wakeRules(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, llvm::Value* host,
                               const std::vector<RuleTrigger>& triggers) {
  if (triggers.empty()) return;
  llvm::Type* i32 = b.getInt32Ty();
  llvm::Type* i64 = b.getInt64Ty();
  llvm::Type* ptr = b.getPtrTy();
  llvm::Value* ruleWords = b.CreateZExt(contextField(f, b, kContextRuleWords, i32), i64);
  llvm::Value* candidates =
      b.CreateInBoundsGEP(i64, b.CreateLoad(ptr, contextField(f, b, kContextCandidates, ptr)),
                          b.CreateMul(b.CreateZExt(host, i64), ruleWords));
  for (const RuleTrigger& t : triggers) {
    llvm::BasicBlock* wake = newBlock(f, "wake" + std::to_string(t.rule));
    llvm::BasicBlock* done = newBlock(f, "woken" + std::to_string(t.rule));
    llvm::Value* present = b.getTrue();
    for (meldvm::PredId q : t.needs)
      present = b.CreateAnd(
          present, b.CreateICmpNE(b.CreateLoad(i32, listHead(f, b, heads, q, kHeadSize)), b.getInt32(0)));
    b.CreateCondBr(present, wake, done);
    b.SetInsertPoint(wake);
    llvm::Value* word = b.CreateConstInBoundsGEP1_64(i64, candidates, t.rule / 64);
    b.CreateStore(b.CreateOr(b.CreateLoad(i64, word), b.getInt64(std::uint64_t(1) << (t.rule % 64))), word);
    b.CreateBr(done);
    b.SetInsertPoint(done);
  }
}

}  // namespace meldc::native::detail
