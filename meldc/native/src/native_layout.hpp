// The layout of native_abi.h's structs as the lowering addresses them: the fields of each, in
// order, as LLVM struct field numbers or byte offsets, each checked against the C struct at
// compile time (a field added on one side only does not build). Private to meldc/native.
#pragma once

#include <cstddef>
#include <cstdint>

#include "meldvm/native_abi.h"

namespace meldc::native::detail {

// Fields of meld_native_helpers (native_abi.h), in order.
enum Helper : unsigned {
  kAbiVersion,
  kLoop,
  kSteps,
  kTest,
  kConsume,
  kUpdated,
  kSlotArgs,
  kReleaseLast,
  kLoopBegin,
  kBuiltins,
  kDerive,
  kSend,
  kUpdate
};
// Fields of meld_native_loop and meld_native_slot, in order.
enum LoopField : unsigned {
  kLoopSlots,
  kLoopWords,
  kLoopStop,
  kLoopSharedStop,
  kLoopFirst,
  kLoopStride,
  kLoopNextWord,
  kLoopArgOffset
};
enum SlotField : unsigned { kSlotPred, kSlotNode, kSlotFact, kSlotFlags, kSlotFixed };
// Fields of meld_native_context, meld_native_table and meld_native_frame_head, in order.
enum ContextField : unsigned {
  kContextInterpreter,
  kContextTables,
  kContextHeadPages,
  kContextStepsLeft,
  kContextFactsTried,
  kContextStop,
  kContextSharedStop,
  kContextConsumed,
  kContextFactsConsumed,
  kContextRunConsumed,
  kContextRulesFired,
  kContextDerivations,
  kContextCandidates,
  kContextFactsDerived,
  kContextRunDerived,
  kContextSendsBuffered,
  kContextLiveBelow,
  kContextSent,
  kContextSentArgs,
  kContextFactsSent,
  kContextDerived,
  kContextDerivedArgs,
  kContextSentPersistent,
  kContextHeap,
  kContextGlobals,
  kContextHeadsPerNode,
  kContextRuleWords
};
enum TableField : unsigned {
  kTableWords,
  kTableStride,
  kTableArgOffset,
  kTableFlags,
  kTableReserved,
  kTableFreeList,
  kTableLive,
  kTableFields
};
enum HeadWord : unsigned { kHeadFirst, kHeadLast, kHeadSize };  // of a list head (ListHead)
enum FrameHeadField : unsigned { kFrameSlots = 3, kFrameHost = 6, kFrameNegative, kFrameUpdated };
static_assert(offsetof(meld_native_context, tables) == 8 * kContextTables &&
              offsetof(meld_native_context, head_pages) == 8 * kContextHeadPages &&
              offsetof(meld_native_context, steps_left) == 8 * kContextStepsLeft &&
              offsetof(meld_native_context, facts_tried) == 8 * kContextFactsTried &&
              offsetof(meld_native_context, stop) == 8 * kContextStop &&
              offsetof(meld_native_context, shared_stop) == 8 * kContextSharedStop &&
              offsetof(meld_native_context, consumed) == 8 * kContextConsumed &&
              offsetof(meld_native_context, facts_consumed) == 8 * kContextFactsConsumed &&
              offsetof(meld_native_context, run_consumed) == 8 * kContextRunConsumed &&
              offsetof(meld_native_context, rules_fired) == 8 * kContextRulesFired &&
              offsetof(meld_native_context, derivations) == 8 * kContextDerivations &&
              offsetof(meld_native_context, candidates) == 8 * kContextCandidates &&
              offsetof(meld_native_context, facts_derived) == 8 * kContextFactsDerived &&
              offsetof(meld_native_context, run_derived) == 8 * kContextRunDerived &&
              offsetof(meld_native_context, sends_buffered) == 8 * kContextSendsBuffered &&
              offsetof(meld_native_context, live_below) == 8 * kContextLiveBelow &&
              offsetof(meld_native_context, sent) == 8 * kContextSent &&
              offsetof(meld_native_context, sent_args) == 8 * kContextSentArgs &&
              offsetof(meld_native_context, facts_sent) == 8 * kContextFactsSent &&
              offsetof(meld_native_context, derived) == 8 * kContextDerived &&
              offsetof(meld_native_context, derived_args) == 8 * kContextDerivedArgs &&
              offsetof(meld_native_context, sent_persistent) == 8 * kContextSentPersistent &&
              offsetof(meld_native_context, heap) == 8 * kContextHeap &&
              offsetof(meld_native_context, globals) == 8 * kContextGlobals &&
              offsetof(meld_native_context, heads_per_node) == 8 * kContextHeadsPerNode &&
              offsetof(meld_native_context, rule_words) == 8 * kContextHeadsPerNode + 4 &&
              sizeof(meld_native_context) == 8 * kContextHeadsPerNode + 8);
enum HeapField : unsigned { kHeapCellFreeList, kHeapBump, kHeapBumpEnd, kHeapLive, kHeapBytesInUse };
static_assert(offsetof(meld_native_heap, bump) == 8 * kHeapBump &&
              offsetof(meld_native_heap, bump_end) == 8 * kHeapBumpEnd &&
              offsetof(meld_native_heap, live) == 8 * kHeapLive &&
              offsetof(meld_native_heap, bytes_in_use) == 8 * kHeapBytesInUse &&
              sizeof(meld_native_heap) == 40);
static_assert(offsetof(meld_native_consumed, size) == 8 && offsetof(meld_native_consumed, capacity) == 12);
static_assert(offsetof(meld_native_array, size) == 8 && offsetof(meld_native_array, capacity) == 12);
// A sent fact's fields by byte.
enum SentFactByte : unsigned {
  kSentNode = 0,
  kSentPred = 4,
  kSentNegative = 8,
  kSentArgs = 12,
  kSentDelay = 16,
  kSentCancelled = 20
};
static_assert(offsetof(meld_native_sent_fact, pred) == kSentPred &&
              offsetof(meld_native_sent_fact, negative) == kSentNegative &&
              offsetof(meld_native_sent_fact, args) == kSentArgs &&
              offsetof(meld_native_sent_fact, delay_ms) == kSentDelay &&
              offsetof(meld_native_sent_fact, cancelled) == kSentCancelled &&
              sizeof(meld_native_sent_fact) == 24);
static_assert(offsetof(meld_native_table, stride) == 8 && offsetof(meld_native_table, arg_offset) == 12 &&
              offsetof(meld_native_table, flags) == 16 && offsetof(meld_native_table, free_list) == 24 &&
              offsetof(meld_native_table, live) == 32 && offsetof(meld_native_table, fields) == 40 &&
              sizeof(meld_native_table) == 48);
enum FieldIndexField : unsigned { kIndexEntries, kIndexMask, kIndexSize, kIndexLinkWord, kIndexInteger };
static_assert(offsetof(meld_native_field_index, mask) == 8 && offsetof(meld_native_field_index, size) == 16 &&
              offsetof(meld_native_field_index, link_word) == 24 &&
              offsetof(meld_native_field_index, integer) == 28 && sizeof(meld_native_field_index) == 32);
static_assert(offsetof(meld_native_frame_head, slots) == 8 * kFrameSlots &&
              offsetof(meld_native_frame_head, host) == 8 * kFrameHost &&
              offsetof(meld_native_frame_head, negative) == 8 * kFrameHost + 4 &&
              offsetof(meld_native_frame_head, updated) == 8 * kFrameHost + 5);
enum Status : std::int32_t { kNotFired = 0, kFired = 1, kReturn = 2 };
// The LLVM struct of the helpers ({i32, ptr, ...}) puts field k at 8 * k: so must the C one.
static_assert(offsetof(meld_native_helpers, loop) == kLoop * 8 &&
              offsetof(meld_native_helpers, steps) == kSteps * 8 &&
              offsetof(meld_native_helpers, test) == kTest * 8 &&
              offsetof(meld_native_helpers, consume) == kConsume * 8 &&
              offsetof(meld_native_helpers, updated) == kUpdated * 8 &&
              offsetof(meld_native_helpers, slot_args) == kSlotArgs * 8 &&
              offsetof(meld_native_helpers, release_last) == kReleaseLast * 8 &&
              offsetof(meld_native_helpers, loop_begin) == kLoopBegin * 8 &&
              offsetof(meld_native_helpers, builtins) == kBuiltins * 8 &&
              offsetof(meld_native_helpers, derive) == kDerive * 8 &&
              offsetof(meld_native_helpers, send) == kSend * 8 &&
              offsetof(meld_native_helpers, update) == kUpdate * 8 &&
              sizeof(meld_native_helpers) == (kUpdate + 1) * 8);
static_assert(offsetof(meld_native_loop, words) == 8 * kLoopWords &&
              offsetof(meld_native_loop, stop) == 8 * kLoopStop &&
              offsetof(meld_native_loop, shared_stop) == 8 * kLoopSharedStop &&
              offsetof(meld_native_loop, first) == 8 * kLoopFirst &&
              offsetof(meld_native_loop, stride) == 8 * kLoopFirst + 4 &&
              offsetof(meld_native_loop, next_word) == 8 * kLoopFirst + 8 &&
              offsetof(meld_native_loop, arg_offset) == 8 * kLoopFirst + 12 &&
              sizeof(meld_native_loop) == 48);
static_assert(offsetof(meld_native_slot, fact) == 4 * kSlotFact && offsetof(meld_native_slot, fixed) == 16 &&
              sizeof(meld_native_slot) == 24);

}  // namespace meldc::native::detail
