// The lowering of one code block (lower_block.cpp: functions and the switch over opcodes;
// lower_facts.cpp: loops over the fact store, FIRE, LOAD/TEST runs, built-in calls and reference
// counts). Private to meldc/native.
#pragma once

#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Module.h>

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "lower_block.hpp"
#include "meldvm/builtin_signatures.hpp"
#include "meldvm/bytecode_internal.hpp"
#include "native_layout.hpp"

namespace meldc::native::detail {

using meldvm::Opcode;

class RegionLowering {
 public:
  RegionLowering(NativeTypes& t, const meldvm::Program& program, const meldvm::CodeBlock& block,
                 std::string prefix, BlockKind kind)
      : t_(t),
        program_(program),
        block_(block),
        code_(block.code),
        prefix_(std::move(prefix)),
        rule_(kind == BlockKind::Rule) {
    // Which loop slots consume the fact they bind (FIRE has nothing to consume past the last).
    meldvm::detail::forEachInstruction(code_, [&](std::size_t pc) {
      if (!meldvm::detail::isLoop(code_[pc])) return;
      const std::uint32_t pred = code_[pc + 1], slot = code_[pc + 2];
      if (code_[pc + 3] & meldvm::kIterConsume) {
        consumingSlots_.insert(slot);
      }
      const auto [it, fresh] = slotPreds_.try_emplace(slot, pred);
      if (!fresh && it->second != pred) it->second = -1;
    });
    // A persistent process's slot 0 holds the fact that triggered it (any predicate it names).
    if (kind == BlockKind::Process) slotPreds_.erase(0);
    planQueensSites();
  }

  // The function for the code entered at `start` (created on first request, lowered at once).
  // The block's start and the bodies of ITER_SORTED loops (run by the VM's loop helper) are
  // meld_native_block functions; a body that native code loops over also gets the loops array
  // (what loop_begin said about each loop slot bound natively: `bound` lists them).
  llvm::Function* region(std::uint32_t start, const std::set<std::uint32_t>& bound = {},
                         bool nativeBody = false);
  // The block's external entry: region(0), or for a rule that consumes facts of known predicates,
  // a function that runs region(0) and then unlinks the facts consumed (lower_unlink.cpp).
  llvm::Function* entry();

 private:
  struct Function {
    llvm::Function* fn = nullptr;
    llvm::Value* helpers = nullptr;
    llvm::Value* vm = nullptr;
    llvm::Value* frame = nullptr;
    llvm::Value* regs = nullptr;
    llvm::Value* lastFired = nullptr;   // exec()'s `lastFired`: did the latest loop fire
    llvm::BasicBlock* entry = nullptr;  // where the stack variables are allocated
    llvm::Value* loops = nullptr;       // meld_native_loop* per slot (those in `bound` are set)
    std::set<std::uint32_t> bound;      // slots bound by a native loop around this code
    std::map<std::uint32_t, llvm::BasicBlock*> blocks;
    std::vector<std::uint32_t> pending;
  };

  llvm::BasicBlock* at(Function& f, std::uint32_t pc) {
    auto [it, fresh] = f.blocks.try_emplace(pc, nullptr);
    if (fresh) {
      it->second = newBlock(f, "pc" + std::to_string(pc));
      f.pending.push_back(pc);
    }
    return it->second;
  }

  void lowerRegion(Function& f, std::uint32_t start, bool nativeBody);

  std::uint32_t length(std::uint32_t pc) const {
    std::string why;
    const std::size_t len = meldvm::detail::instructionLength(code_, pc, why);
    if (len == 0) throw NativeError("block '" + block_.label + "': " + why);  // verified: cannot happen
    return std::uint32_t(len);
  }

  // ---- helpers and registers ----
  // The helper table is constant while a program runs: its loads may be merged and hoisted.
  llvm::Value* invariantLoad(llvm::IRBuilder<>& b, llvm::Value* address) {
    llvm::LoadInst* load = b.CreateLoad(b.getPtrTy(), address);
    load->setMetadata(llvm::LLVMContext::MD_invariant_load, llvm::MDNode::get(t_.context, {}));
    return load;
  }
  llvm::Value* helper(Function& f, llvm::IRBuilder<>& b, Helper h) {
    return invariantLoad(b, b.CreateStructGEP(t_.helpersType, f.helpers, h));
  }
  llvm::Value* reg(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {
    return b.CreateConstInBoundsGEP1_64(b.getInt64Ty(), f.regs, r);
  }
  llvm::Value* loadReg(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {
    return b.CreateLoad(b.getInt64Ty(), reg(f, b, r));
  }
  llvm::Value* loadInt(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {  // Value::asInt
    return b.CreateTrunc(loadReg(f, b, r), b.getInt32Ty());
  }
  llvm::Value* loadFloat(Function& f, llvm::IRBuilder<>& b, std::uint32_t r) {  // Value::asFloat
    return b.CreateBitCast(loadReg(f, b, r), b.getDoubleTy());
  }
  void storeInt(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* i32) {  // fromInt
    b.CreateStore(b.CreateSExt(i32, b.getInt64Ty()), reg(f, b, r));
  }
  void storeFloat(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* d) {
    b.CreateStore(b.CreateBitCast(d, b.getInt64Ty()), reg(f, b, r));
  }
  void storeBool(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* i1) {
    b.CreateStore(b.CreateZExt(i1, b.getInt64Ty()), reg(f, b, r));
  }
  void step(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc) {  // steps[opcode](vm, frame, pc)
    llvm::Value* entry = b.CreateConstInBoundsGEP1_64(b.getPtrTy(), helper(f, b, kSteps), code_[pc]);
    b.CreateCall(t_.stepType, invariantLoad(b, entry), {f.vm, f.frame, b.getInt32(pc)});
    b.CreateBr(at(f, pc + length(pc)));
  }
  void branch(Function& f, llvm::IRBuilder<>& b, llvm::Value* cond, std::uint32_t yes, std::uint32_t no) {
    b.CreateCondBr(cond, at(f, yes), at(f, no));
  }
  void ret(llvm::IRBuilder<>& b, Status s) { b.CreateRet(b.getInt32(s)); }

  // A stack variable of the function (in its entry block, where mem2reg promotes it).
  llvm::AllocaInst* local(Function& f, llvm::Type* type, const char* name) {
    llvm::IRBuilder<> e(f.entry, f.entry->getFirstInsertionPt());
    return e.CreateAlloca(type, nullptr, name);
  }
  llvm::BasicBlock* newBlock(Function& f, const std::string& name) {
    return llvm::BasicBlock::Create(t_.context, name, f.fn);
  }

  // What loop_begin said about a loop (meld_native_loop), read where it is needed.
  struct LoopView {
    llvm::Value* slots;   // the frame's meld_native_slot array
    llvm::Value* words;   // where the predicate's slot array is
    llvm::Value* stride;  // i64
    llvm::Value* argOffset;
  };
  llvm::Value* loopField(llvm::IRBuilder<>& b, llvm::Value* info, LoopField k, llvm::Type* type);
  LoopView loadLoopView(llvm::IRBuilder<>& b, llvm::Value* info);
  // The loop that bound slot s around this code (s is in f.bound).
  LoopView loopView(Function& f, llvm::IRBuilder<>& b, std::uint32_t s);
  // The view of a loop over pred, from the context and the frame (invariant loads).
  LoopView tableView(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred);
  llvm::Value* slotField(llvm::IRBuilder<>& b, llvm::Value* slots, std::uint32_t s, SlotField k) {
    return b.CreateStructGEP(t_.slotType, b.CreateConstInBoundsGEP1_64(t_.slotType, slots, s), k);
  }
  // The address of word w of fact `fact` (the array is read each time: a body may grow it).
  llvm::Value* factWord(llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact, llvm::Value* w);
  llvm::Value* highHalf(llvm::IRBuilder<>& b, llvm::Value* fact, const LoopView& loop, llvm::Value* w);
  llvm::Value* factCount(llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact);

  // The loop's end: the same status as the interpreter's (lastFired, or return when stopping).
  void endLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc, llvm::Value* fired,
               llvm::Value* stopping);

  void lowerLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);

  // ITER and ITER_KEY: the slot is bound and the first fact found (by beginLoop, or the VM's
  // loop_begin); the facts are stepped through here, in the order, with the skips and the counts
  // of Interpreter::loop.
  void lowerNativeLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  // An ITER or ITER_KEY at the host begins as loop_begin would, from meld_native_context: the
  // slot bound, the step counted (at the limit the VM's loop_begin is called, which throws), the
  // first fact read from the host's list head (ITER) or looked up in the index (ITER_KEY, where
  // the argument has an integer index; loop_begin looks the others up). Returns the first fact
  // and the word that links the loop's facts (i64). `info` is filled as loop_begin fills it only
  // when fillInfo (the code inside reads that loop's view from f.loops).
  std::pair<llvm::Value*, llvm::Value*> beginLoop(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc,
                                                  llvm::Value* info, bool fillInfo);
  // The first fact of `host` whose argument `field` is `key` (i64 bits), through the integer index
  // `index` (a meld_native_field_index*), as FactTable::firstWithKey finds it; MELD_NATIVE_NO_FACT
  // if none (lower_keys.cpp).
  llvm::Value* findWithKey(Function& f, llvm::IRBuilder<>& b, const LoopView& table, llvm::Value* index,
                           llvm::Value* host, std::uint32_t field, llvm::Value* key);
  // meldvm/key_hash.hpp's folded hash of an integer key (i64 bits) at node `host` (i32).
  llvm::Value* foldedKeyHash(llvm::IRBuilder<>& b, llvm::Value* host, llvm::Value* key);
  // The address of node's list heads (an i32 node), and of word w of its head of pred's list.
  llvm::Value* nodeHeads(Function& f, llvm::IRBuilder<>& b, llvm::Value* node);
  llvm::Value* listHead(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                        HeadWord w);
  llvm::Value* contextField(Function& f, llvm::IRBuilder<>& b, ContextField k, llvm::Type* type) {
    llvm::LoadInst* load = b.CreateLoad(type, b.CreateStructGEP(t_.contextType, f.vm, k));
    load->setMetadata(llvm::LLVMContext::MD_invariant_load, llvm::MDNode::get(t_.context, {}));
    return load;
  }
  // Before visiting `fact`, a loop that reads its facts' lists fetches the lists of the facts
  // ahead down to maxDepth (detail::listFetchDepth), as the interpreter's walkListsAhead does.
  void fetchListsAhead(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact,
                       llvm::Value* nextWord, std::uint32_t field, int maxDepth);
  // The same, carried from one visit to the next when the lists stay put (detail::listsStayPut,
  // lower_list_pipeline.cpp): the cell on the way for each fact ahead, and the fact furthest on.
  struct ListPipe {
    llvm::ArrayType* cellsType = nullptr;
    llvm::AllocaInst* cells = nullptr;  // [k - 1]: the cell of the fact k on (0: none)
    llvm::AllocaInst* ahead = nullptr;
  };
  // Before the loop's first visit (of `first`), and before each later one.
  ListPipe startListPipeline(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* first,
                             llvm::Value* nextWord, std::uint32_t field);
  void stepListPipeline(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, const ListPipe& pipe,
                        llvm::Value* nextWord, std::uint32_t field);
  llvm::Value* tailOrNull(Function& f, llvm::IRBuilder<>& b, llvm::Value* cell);
  std::pair<llvm::Value*, llvm::Value*> nextWithList(Function& f, llvm::IRBuilder<>& b, const LoopView& loop,
                                                     llvm::Value* fact, llvm::Value* nextWord,
                                                     std::uint32_t field);
  void fetchCell(llvm::IRBuilder<>& b, const ListPipe& pipe, int k, llvm::Value* cell);

  void lowerInstruction(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);

  bool boxed(std::uint32_t r) const { return program_.types.boxed(block_.registerTypes[r]); }
  bool bitsAreIdentity(meldvm::TypeId t) const {  // equal values, equal bits
    const meldvm::TypeKind k = program_.types.kind(t);
    return k == meldvm::TypeKind::Int || k == meldvm::TypeKind::Bool || k == meldvm::TypeKind::Node ||
           k == meldvm::TypeKind::Thread;
  }
  // The fields of pred that hold heap objects (lists, strings, structs, arrays, sets), in order.
  std::vector<std::uint32_t> boxedFields(std::uint32_t pred) const {
    std::vector<std::uint32_t> out;
    const std::vector<meldvm::TypeId>& fields = program_.predicates[pred].fields;
    for (std::uint32_t i = 0; i < fields.size(); ++i)
      if (program_.types.boxed(fields[i])) out.push_back(i);
    return out;
  }

  // The predicate a loop slot holds facts of, when every loop that binds it has the same one
  // (otherwise, or for a process's trigger slot, unknown: -1).
  std::int64_t slotPredicate(std::uint32_t slot) const {
    auto it = slotPreds_.find(slot);
    return it == slotPreds_.end() ? -1 : it->second;
  }
  // Whether TEST at pc compares an int, bool, node or thread field: then equality is of the bits.
  bool integerTest(std::uint32_t pc) const {
    const std::int64_t p = slotPredicate(code_[pc + 1]);
    if (p < 0) return false;
    const meldvm::TypeKind k = program_.types.kind(program_.predicates[std::size_t(p)].fields[code_[pc + 2]]);
    return k == meldvm::TypeKind::Int || k == meldvm::TypeKind::Bool || k == meldvm::TypeKind::Node ||
           k == meldvm::TypeKind::Thread;
  }
  bool inSlotRun(std::uint32_t pc, std::uint32_t slot) const {
    if (pc >= code_.size() || code_[pc + 1] != slot) return false;
    const Opcode op = Opcode(code_[pc]);
    return op == Opcode::LOAD || (op == Opcode::TEST && integerTest(pc));
  }

  // Reference counts adjusted inline (a boxed value points at its 32-bit count; nil holds none):
  // only a count that would reach zero calls the VM.
  void adjustCount(Function& f, llvm::IRBuilder<>& b, llvm::Value* v, bool retain, std::uint32_t type);
  // Before a boxed register takes `value`: the interpreter's retain, then setReg's release of the
  // old value.
  void setBoxed(Function& f, llvm::IRBuilder<>& b, std::uint32_t r, llvm::Value* value);

  // CONS (lower_cons.cpp): the cell made inline where consInline says the element allows it.
  bool consInline(std::uint32_t listType) const;
  void lowerCons(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  // DERIVE, SEND and UPDATE: the registers' values gathered here (constant register numbers, no
  // decoding) and handed to the helper for that opcode.
  void lowerFactOut(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  // SEND and DERIVE (lower_writes.cpp): appended to the run's sent or derived facts when
  // meld_native_context allows it, through the send or derive helper otherwise.
  void lowerSend(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  void lowerDerive(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  // Whether native code may write a fact of pred itself: its table has `flag`
  // (MELD_NATIVE_TABLE_*), no derivation is being recorded, the frame is not negative (unless
  // anySign).
  llvm::Value* writesHere(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred, std::uint32_t flag,
                          bool anySign = false);
  // If every condition holds, on in a new block named `name`, where the builder is left; else
  // `viaVm` (which ends its block: the helper's call, then a branch on).
  void hereOrVm(Function& f, llvm::IRBuilder<>& b, std::span<llvm::Value* const> conditions,
                const std::string& name, const std::function<void()>& viaVm);
  // A buffered fact if the conditions both share (the table's flag, no derivation recorded, not
  // negative, room in both arrays) and `more` hold: the record and its arguments appended and
  // facts_derived and run_derived counted, the builder left at the end of that path. Else the
  // helper call made by `viaVm`, then a branch to `next`. A buffer `withSign` (persistent facts
  // sent) takes negative frames too: the record keeps the sign, and a retraction is not counted.
  struct Buffer {
    ContextField facts, args;
    std::uint32_t flag = MELD_NATIVE_TABLE_BUFFERED;
    bool withSign = false;
  };
  void appendFact(Function& f, llvm::IRBuilder<>& b, Buffer buffer, llvm::Value* node, std::uint32_t pred,
                  llvm::Value* args, std::uint32_t count, llvm::Value* more, llvm::BasicBlock* next,
                  const std::function<void()>& viaVm);
  // UPDATE (lower_writes.cpp): in place when meld_native_context allows it (a plain table, the
  // host's fact, no derivation recorded, not negative) and the predicate's rules need no thread
  // fact; through the update helper otherwise.
  void lowerUpdate(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  // A rule over the predicate, and the other predicates of its body (ProgramTables' trigger).
  struct RuleTrigger {
    std::uint32_t rule;
    std::vector<meldvm::PredId> needs;
  };
  // The rules whose body names pred, in rule order; none if one of them names a thread predicate.
  std::optional<std::vector<RuleTrigger>> triggersOf(std::uint32_t pred) const;
  // The address of pred's meld_native_table.
  llvm::Value* tableOf(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred) {
    return b.CreateConstInBoundsGEP1_64(t_.tableType, contextField(f, b, kContextTables, b.getPtrTy()), pred);
  }
  // pred's table as native code that writes facts sees it (lower_lists.cpp): its fields, and its
  // slot array and stride as they are where this is made.
  struct TableWords {
    llvm::IRBuilder<>& b;
    llvm::StructType* type;
    llvm::Value* table;
    llvm::Value* words = nullptr;   // the slot array
    llvm::Value* stride = nullptr;  // i64
    llvm::Value* field(TableField k, llvm::Type* t) const {
      return b.CreateLoad(t, b.CreateStructGEP(type, table, k));
    }
    llvm::Value* word0(llvm::Value* fact) const {  // the address of the fact's first word
      return b.CreateInBoundsGEP(b.getInt64Ty(), words,
                                 b.CreateMul(b.CreateZExt(fact, b.getInt64Ty()), stride));
    }
  };
  TableWords tableWords(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred);
  // Before the body runs for `fact`, the index entry its next fact's key will be looked up in is
  // fetched (a hint): the look-ups of consecutive facts land anywhere in the index's table, and
  // each waited for its entry (a third of new-heat-transfer's misses).
  void fetchKeyAhead(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, llvm::Value* fact,
                     llvm::Value* nextWord, const meldvm::detail::KeyJoin& join);
  // The predicates whose linear facts may have an index (the VM's ProgramTables::keyLookups: the
  // program's index declarations and ITER_KEY loops), found once per block lowered.
  const std::set<std::uint32_t>& indexedLinear();
  // The update of a MELD_NATIVE_TABLE_KEYED table's fact goes on here only where its index chains
  // stay as they are; `viaVm` otherwise. (A plain table's goes on at once.)
  void keysKeptOrVm(Function& f, llvm::IRBuilder<>& b, const TableWords& table, llvm::Value* fact,
                    llvm::Value* args, std::uint32_t count, bool toBack, const std::function<void()>& viaVm);
  // The list primitives of FactTable on a node's list of pred (its heads at `heads`): word 0 of a
  // fact links it, its previous fact in the low half and its next one in the high half
  // (MELD_NATIVE_NO_FACT at either end, where the list head's first or last is written instead).
  // connect: p and nx become neighbours (FactTable::connect); moveToBack (FactTable::moveToBack);
  // linkLast: a fact linked at the end (FactTable::fill's links). setHalf writes one half of a word.
  void setHalf(llvm::IRBuilder<>& b, llvm::Value* word, llvm::Value* v, bool high);
  void connect(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred, const TableWords& t,
               llvm::Value* p, llvm::Value* nx);
  void connectEnd(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                  const TableWords& t, llvm::Value* at, HeadWord headWord, llvm::Value* other);
  void moveToBack(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                  const TableWords& t, llvm::Value* fact);
  void linkLast(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, std::uint32_t pred,
                const TableWords& t, llvm::Value* fact);
  // Machine::factAdded for the host's new fact of the triggers' predicate.
  void wakeRules(Function& f, llvm::IRBuilder<>& b, llvm::Value* heads, llvm::Value* host,
                 const std::vector<RuleTrigger>& triggers);
  // The registers regs[0, count) stored in a stack array of the function, which is returned.
  llvm::Value* gatherArgs(Function& f, llvm::IRBuilder<>& b, const std::uint32_t* regs, std::uint32_t count);

  // CALL: the built-in's implementation is called directly (builtins[id]) with the registers'
  // values; its result is owned, so a boxed register only lets go of its old value. fabs is inline.
  void lowerCall(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);
  // A loop over a list's cells (lower_queens.cpp): `head`, entered from the block the builder was
  // in, has phis for the cell (`at`, 0 at the list's end) and its distance (1 for the first cell,
  // of the type asked); stepCellWalk goes on with the cell's tail, the distance one more.
  struct CellWalk {
    llvm::BasicBlock* head;
    llvm::PHINode* at;
    llvm::PHINode* distance;
  };
  CellWalk beginCellWalk(Function& f, llvm::IRBuilder<>& b, llvm::Value* list, llvm::Type* distanceType,
                         const std::string& name);
  void stepCellWalk(llvm::IRBuilder<>& b, const CellWalk& w);
  // Word MELD_NATIVE_LIST_HEAD_WORD or _TAIL_WORD of the list cell at address `cell` (an i64).
  llvm::Value* cellWord(llvm::IRBuilder<>& b, llvm::Value* cell, unsigned word) {
    return b.CreateLoad(b.getInt64Ty(), b.CreateConstInBoundsGEP1_64(
                                            b.getInt64Ty(), b.CreateIntToPtr(cell, b.getPtrTy()), word));
  }
  // queens_violation(Y, L) as a loop over L's cells in the block itself (lower_queens.cpp).
  llvm::Value* queensViolation(Function& f, llvm::IRBuilder<>& b, llvm::Value* row, llvm::Value* list);
  // A call of queens_violation whose list register some loop around it keeps: the rows its list
  // rules out are gathered once into a mask, in two words after the loops' array (`word`: the
  // state, kRows*; then the mask), until the register is written again.
  struct QueensSite {
    std::uint32_t word;     // index of the state word in f.loops, in 8-byte words
    std::uint32_t listReg;  // L's register
  };
  static constexpr std::uint64_t kRowsUnknown = 0, kRowsMasked = 1, kRowsWalked = 2;  // too long a list
  void planQueensSites();  // fills queensSites_ and queensWords_
  llvm::Value* queensWord(Function& f, llvm::IRBuilder<>& b, const QueensSite& site, std::uint32_t k) {
    return b.CreateConstInBoundsGEP1_64(b.getInt64Ty(), f.loops, site.word + k);
  }
  // The state words of the sites whose list is register `written` (-1: none) back to unknown: an
  // instruction that writes it is lowered next.
  void forgetQueensRows(Function& f, llvm::IRBuilder<>& b, std::int64_t written);
  void forgetAllQueensRows(Function& f, llvm::IRBuilder<>& b);  // a loops' array of the function's own
  // One walk of the list: the mask of the rows in [0, 64) its queens rule out, and whether the
  // whole list was walked (false for a list of kLongestMaskedList cells or more).
  std::pair<llvm::Value*, llvm::Value*> queensRows(Function& f, llvm::IRBuilder<>& b, llvm::Value* list);
  // queens_violation(row, list) from the site's mask (gathered at its first call), or from the walk
  // for a row outside [0, 64) or a list too long for the mask.
  llvm::Value* cachedQueensViolation(Function& f, llvm::IRBuilder<>& b, const QueensSite& site,
                                     llvm::Value* row, llvm::Value* list);

  // LOADs and TESTs of integer-like fields, one after the other on the same slot: its arguments
  // are looked up once and read in place (nothing stores a fact in between: a release that frees
  // a value touches the heap, not the fact store).
  void lowerSlotRun(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc);

  // FIRE and CFIRE: the interpreter's fire(), reading the slots of native loops in place and
  // consuming their facts (the VM is called for a slot a native loop did not bind, or when the
  // array of consumed facts is full).
  void lowerFire(Function& f, llvm::IRBuilder<>& b, std::uint32_t pc, bool rule);
  // Machine::consumed for the live fact `fact` of native loop slot s: its count set to 0, appended
  // to the consumed facts, counted.
  void consumeFact(Function& f, llvm::IRBuilder<>& b, const LoopView& loop, std::uint32_t s,
                   llvm::Value* fact);
  void increment(llvm::IRBuilder<>& b, llvm::Value* counter) {
    b.CreateStore(b.CreateAdd(b.CreateLoad(b.getInt64Ty(), counter), b.getInt64(1)), counter);
  }

  // At the end of a rule run (lower_rule_end.cpp): a predicate whose consumed facts the rule
  // unlinks itself, or whose derived facts it stores itself, and the rules over it.
  struct PredicateRules {
    std::uint32_t pred;
    std::vector<RuleTrigger> triggers;
  };
  std::vector<PredicateRules> unlinkedPredicates() const;
  std::vector<PredicateRules> derivedPredicates() const;
  // An array of records the VM reads after the rule run: `size` of them at `data`, `bytes` each,
  // the predicate's 32-bit id at byte `predByte`, the array's size stored at `sizeAt`.
  struct Records {
    std::string name;
    llvm::Value *data, *size, *sizeAt;
    std::uint32_t bytes, predByte;
  };
  // handle(u, record, vm): the record of u.pred handled, the builder left where the loop goes on
  // (or a branch to vm, where the loop stops).
  using HandleRecord = std::function<void(const PredicateRules&, llvm::Value*, llvm::BasicBlock*)>;
  // atEnd(all handled, how many were handled), with the array's new size stored.
  using AtEnd = std::function<void(bool, llvm::Value*)>;
  // A loop over the records in order, handling each whose predicate is one of `preds`; at the
  // first other one (or at a branch to `vm`) it stops, and that record and those after it are
  // moved to the front of the array for the VM. Then atEnd and a branch to `allDone` when all
  // were handled, to `done` otherwise.
  void recordLoop(Function& f, llvm::IRBuilder<>& b, const Records& records,
                  const std::vector<PredicateRules>& preds, const HandleRecord& handle, const AtEnd& atEnd,
                  llvm::BasicBlock* allDone, llvm::BasicBlock* done);
  // From the start of the consumed facts' array (`size` of them): a loop that unlinks each one
  // and stops at the first it does not handle (another predicate, a table that is not plain),
  // leaving that one and the rest to the VM. Ends in a branch to `all` when it unlinked them all,
  // to `done` otherwise.
  void unlinkConsumed(Function& f, llvm::IRBuilder<>& b, const std::vector<PredicateRules>& unlinked,
                      llvm::Value* consumed, llvm::Value* size, llvm::BasicBlock* all,
                      llvm::BasicBlock* done);
  // tableWords(pred), on in a new block when the table is MELD_NATIVE_TABLE_PLAIN (else a branch
  // to vm).
  TableWords plainTableOrVm(Function& f, llvm::IRBuilder<>& b, std::uint32_t pred, llvm::BasicBlock* vm);
  // FactTable::erase and Machine::factRemoved for the node's fact of u.pred; to `vm` if its table
  // is not plain (the builder is left after the unlinking otherwise).
  void unlinkFact(Function& f, llvm::IRBuilder<>& b, const PredicateRules& u, llvm::Value* node,
                  llvm::Value* fact, llvm::BasicBlock* vm);
  // Machine::storeDerivedLinear likewise, the same stop; then a branch to `done`.
  void storeDerived(Function& f, llvm::IRBuilder<>& b, const std::vector<PredicateRules>& stored,
                    llvm::BasicBlock* done);
  // Database::addLinearTrusted and Machine::factAdded for a fact of u.pred at the node, its
  // arguments at `args`; to `vm` if its table is not plain or has no free slot.
  void storeFact(Function& f, llvm::IRBuilder<>& b, const PredicateRules& u, llvm::Value* node,
                 llvm::Value* args, llvm::BasicBlock* vm);

  NativeTypes& t_;
  const meldvm::Program& program_;
  std::set<std::uint32_t> consumingSlots_;  // slots some loop binds with kIterConsume
  const std::uint32_t fabsId_ = meldvm::findBuiltin("fabs")->id;
  const std::uint32_t queensId_ = meldvm::findBuiltin("queens_violation")->id;
  std::map<std::uint32_t, QueensSite> queensSites_;  // by the CALL's pc
  std::uint32_t queensWords_ = 0;                    // their words after the loops' array
  std::map<std::uint32_t, std::int64_t> slotPreds_;  // slot -> predicate of every loop binding it
  std::optional<std::set<std::uint32_t>> indexedLinear_;  // indexedLinear(), once asked
  const meldvm::CodeBlock& block_;
  std::span<const std::uint32_t> code_;
  std::string prefix_;
  std::map<std::uint32_t, llvm::Function*> regions_;  // by the pc each function starts at
  const bool rule_;          // a rule's block (Machine::runRule runs it, then finishRuleRun)
  bool wrapsEntry_ = false;  // region(0) is internal, run by entry()'s function
};

}  // namespace meldc::native::detail
