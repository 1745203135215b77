/* The seam between natively compiled Meld code and the VM (plain C).
 *
 * The LLVM backend (meldc/native) lowers the verified bytecode of a code block to functions of type
 * meld_native_block: one for the block's start and one for the body of each of its loops. Register
 * arithmetic, moves of unboxed values, jumps, the beginning and stepping of loops through a
 * predicate's facts (meld_native_context, meld_native_loop), reading facts in place, consuming
 * them, updating them in place, appending the facts a rule derives or sends to the run's buffers,
 * and counting become machine code, in the common cases that meld_native_context describes; the
 * rest of what changes the fact store, the heap, messages or the scheduler is a call to one of the
 * helpers below, which run the interpreter's own code for that instruction. Where native code does
 * the VM's work itself, the tests keep the two in agreement (every conformance golden in every
 * mode, the differential fuzz).
 *
 * A block function returns what the interpreter's exec() returns for the same code: 0 the body did
 * not fire, 1 it fired, 2 return (RET, or the run is stopping). `regs` are the frame's registers,
 * 8 bytes each (meldvm::Value). */
#ifndef MELDVM_NATIVE_ABI_H
#define MELDVM_NATIVE_ABI_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever a helper, its meaning or the block signature changes. (9: the context and the
 * helpers of 2026-11-29; the commits that built them up called theirs 8, with other helper tables:
 * a shared object of one of them is refused, not misread. 10: UPDATE, SEND and DERIVE in native
 * code. 11: a rule's consumed facts unlinked by native code, the table's free list and count. 13:
 * meld_native_context::heap, CONS in native code. 15: meld_native_table::fields, ITER_KEY begun and
 * indexed facts updated in native code; also whenever meldvm/key_hash.hpp changes.) */
#define MELD_NATIVE_ABI_VERSION 15u

typedef struct meld_native_vm meld_native_vm;       /* the VM's meld_native_context (below) */
typedef struct meld_native_frame meld_native_frame; /* its frame (registers, loop slots) */
typedef struct meld_native_helpers meld_native_helpers;

typedef int32_t (*meld_native_block)(const meld_native_helpers* h, meld_native_vm* vm, meld_native_frame* f,
                                     uint64_t* regs);
typedef void (*meld_native_step)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc);
/* A built-in function (builtins.def): its result (owned by the caller) from `count` arguments;
 * `result` is the CALL's concrete result type. */
typedef uint64_t (*meld_native_builtin)(meld_native_vm* vm, const uint64_t* args, uint32_t count,
                                        uint32_t result);

#define MELD_NATIVE_NO_FACT 0xFFFFFFFFu

/* A list value is the address of its first cell (0: the empty list); the 8-byte word
 * MELD_NATIVE_LIST_HEAD_WORD of a cell is its element (a value, as in a register) and word
 * MELD_NATIVE_LIST_TAIL_WORD the address of the next cell. Native code reads them to fetch the
 * lists of the facts a loop visits next (a hint) and in built-ins it inlines (queens_violation). */
#define MELD_NATIVE_LIST_HEAD_WORD 1u
#define MELD_NATIVE_LIST_TAIL_WORD 2u

/* A loop slot of the frame (meldvm::Interpreter::Slot, same layout): the fact a loop has bound,
 * which the helpers (FIRE, UPDATE, why-trees) read. */
typedef struct meld_native_slot {
  uint32_t pred;
  uint32_t node;
  uint32_t fact; /* MELD_NATIVE_NO_FACT when unbound */
  uint32_t flags;
  const uint64_t* fixed; /* a process's trigger: pre-bound arguments instead of a stored fact */
} meld_native_slot;

/* Where a predicate's facts are (one per predicate, in meld_native_context::tables): the slot
 * array's address (it moves when the table grows), a fact's size in words and the word of its
 * first argument (fixed once the VM runs). */
typedef struct meld_native_table {
  const uint64_t* const* words;
  uint32_t stride;
  uint32_t arg_offset;
  uint32_t flags; /* MELD_NATIVE_TABLE_* */
  uint32_t reserved;
  uint32_t* free_list; /* the first free fact (a free fact's word 0 links the next in its high half) */
  uint32_t* live;      /* how many facts the table holds */
  /* One per argument (home excluded), or null when the table has no index: the index on that
   * argument alone (meld_native_field_index). */
  const struct meld_native_field_index* fields;
} meld_native_table;

/* The index of a table on one argument (link_word 0: none). A fact f's word link_word links the
 * facts with its key in list order (the previous in its low half, the next in its high half). The
 * index's hash table maps a key to the first fact with it: `size` entries in use (0: none, and then
 * `entries` may not be there), *mask + 1 entries at *entries (they move when the table grows),
 * each one 8-byte word, its low half the key's folded hash and its high half the fact
 * (MELD_NATIVE_NO_FACT: an empty entry); a key's entry is found by linear probing from its folded
 * hash & mask. With `integer` nonzero the key is an int, bool, node or thread whose hash is
 * meldvm/key_hash.hpp's of the node and the argument's 8 bytes, and a fact has the key when its
 * node (the low half of word 1) and the argument's bytes are the same. */
typedef struct meld_native_field_index {
  const uint64_t* const* entries;
  const uint32_t* mask;
  const uint32_t* size;
  uint32_t link_word;
  uint32_t integer;
} meld_native_field_index;

/* The table's facts are plain words: no index, no de-duplication, no argument that holds a
 * reference. Native code may then write a fact's arguments and relink it in its list itself, and
 * unlink a fact a rule run consumed when the run ends, as meldvm::FactTable::erase does: out of
 * its list (the list head's size one less), its word 1 zero, its word 0 the free list's head in
 * the high half and its previous fact in the low half, the free list's head the fact, `live` one
 * less. */
#define MELD_NATIVE_TABLE_PLAIN 1u
/* The predicate is linear, not an action, and holds no reference: a fact of it derived at the host
 * waits in the derived buffer until the rule run ends, one sent to another node in the sent buffer
 * until the node run ends (meld_native_context::derived, sent). */
#define MELD_NATIVE_TABLE_BUFFERED 2u
/* The predicate is persistent, not an action or a thread predicate, and holds no reference: a fact
 * of it sent to a node, or a retraction of one, waits in the persistent sent buffer until the node
 * run ends (meld_native_context::sent_persistent). */
#define MELD_NATIVE_TABLE_PERSISTENT_SENT 4u
/* The predicate is linear, not an action, and the only references its facts hold are heap objects
 * (boxed fields: no node the VM counts references to): native code that retains each boxed
 * argument itself (its count one more, atomically when the count's top bit says it is shared) may
 * append the fact to the derived or sent buffer as under MELD_NATIVE_TABLE_BUFFERED; the buffer's
 * references then go to the stored fact, as the VM's own appends' do. (A separate flag: native
 * code built before it appends under BUFFERED only, without retaining.) */
#define MELD_NATIVE_TABLE_BUFFERED_BOXED 8u
/* The table has indexes, each on one argument (meld_native_table::fields), no de-duplication and no
 * argument that holds a reference. Native code may then update a fact in place as under
 * MELD_NATIVE_TABLE_PLAIN when every indexed argument keeps its value and, if the fact moves to
 * the end of its list, no fact with the same key follows it (its link words' high halves are
 * MELD_NATIVE_NO_FACT): its index chains keep their order. */
#define MELD_NATIVE_TABLE_KEYED 16u

/* The start of a frame (meldvm::Interpreter::Frame, same layout): the running node and the loop
 * slots, which native code reads to begin a loop itself. */
typedef struct meld_native_frame_head {
  const void* block;
  const uint32_t* code;
  uint64_t* regs;
  meld_native_slot* slots;
  const uint8_t* boxed;
  const uint8_t* slot_flags;
  uint32_t host;
  uint8_t negative; /* the block retracts what it derives (a retraction's run) */
  uint8_t updated;  /* an UPDATE ran in this frame (RET_IF_UPDATED reads it) */
} meld_native_frame_head;

/* A node's list heads: per table, its first fact, its last fact and its size (4 bytes each). A
 * node n's heads are at (*head_pages)[n >> MELD_NATIVE_HEAD_PAGE_SHIFT], node (n & mask) of that
 * page, heads_per_node of them per node. */
#define MELD_NATIVE_HEAD_PAGE_SHIFT 8u
#define MELD_NATIVE_HEAD_WORDS 3u

/* The facts a rule run consumed so far: `size` of them at `facts`, three 4-byte words each (node,
 * predicate, fact), room for `capacity`. The VM unlinks them when the rule run ends, in this
 * order: a rule's native code may unlink the first ones itself before it returns (those of
 * MELD_NATIVE_TABLE_PLAIN tables, in order, each rule over the predicate no longer a candidate at
 * the node when its list is empty, as meldvm::Machine::factRemoved does) and leave the others at
 * the front of the array, for the VM. */
typedef struct meld_native_consumed {
  void* facts;
  uint32_t size;
  uint32_t capacity;
} meld_native_consumed;

/* A growing array of the VM (meldvm::NativeArray, meldvm::ValueBuffer): `size` elements at
 * `data`, room for `capacity`. Native code appends while there is room, and calls the VM when
 * there is none. */
typedef struct meld_native_array {
  void* data;
  uint32_t size;
  uint32_t capacity;
} meld_native_array;

/* A fact sent during a rule run, delivered when the node run ends, or derived at the host, stored
 * when the rule run ends (meldvm::Machine::PendingFact): its node, its predicate, and the word of
 * the arguments' array (meld_native_context::sent_args, derived_args) its arguments start at. */
typedef struct meld_native_sent_fact {
  uint32_t node;
  uint32_t pred;
  uint8_t negative;
  uint32_t args;
  uint32_t delay_ms;
  uint8_t cancelled;
} meld_native_sent_fact;

/* Where CONS takes a list cell (24 bytes: its 32-bit count, its 32-bit type, its head, its tail)
 * without calling the VM: the first block of the heap's free list of 24-byte blocks (a free
 * block's first word is the next one; null when empty), else the room left in the heap's current
 * slab, [*bump, *bump_end); `live` and `bytes_in_use` count what the heap holds (one object and
 * 24 bytes more per cell). With neither, the step helper makes the cell. */
typedef struct meld_native_heap {
  void** cell_free_list;
  char** bump;
  char* const* bump_end;
  uint64_t* live;
  uint64_t* bytes_in_use;
} meld_native_heap;

/* What a block's `vm` argument points at: what native code reads to begin and end an ITER loop,
 * to fire a rule, to update a fact and to derive or send one without calling the VM (the
 * predicate's table, the node's list heads, the step count, the consumed facts, the candidate
 * rules, the buffers of derived and sent facts, the statistics), and the VM itself for the
 * helpers. Constant while the VM runs (what it points at changes). */
typedef struct meld_native_context {
  void* interpreter;                        /* the helpers' */
  const meld_native_table* tables;          /* per predicate */
  const uint32_t* const* const* head_pages; /* the page table of the list heads (it moves) */
  uint64_t* steps_left;       /* a loop counts one step: at 1, loop_begin is called (it throws) */
  uint64_t* facts_tried;      /* the statistics' facts tried */
  const uint8_t* stop;        /* nonzero: the run is stopping (the machine's flag) */
  const uint8_t* shared_stop; /* nonzero: every thread is stopping (an atomic flag) */
  /* A FIRE consumes a fact by setting its count to 0, appending it here and counting it in both
   * counts (when the array is full, the consume helper does it all). */
  meld_native_consumed* consumed;
  uint64_t* facts_consumed; /* the statistics' */
  uint64_t* run_consumed;   /* the node run's */
  uint64_t* rules_fired;    /* the statistics': a FIRE adds one */
  /* An UPDATE changes the fact in place when derivations are not recorded (*derivations is
   * null), the frame is not negative, the table is MELD_NATIVE_TABLE_PLAIN and the fact is the
   * host's; it then makes the rules over the predicate candidates again as the VM's factAdded
   * does (node n's candidate bits: rule_words 64-bit words at (*candidates) + n * rule_words),
   * counts the fact in both counts and sets the frame's `updated`. */
  const void* const* derivations;
  uint64_t* const* candidates; /* (the array moves when nodes are added) */
  uint64_t* facts_derived;     /* the statistics' */
  uint64_t* run_derived;       /* the node run's */
  /* A SEND appends its fact to `sent` and its arguments to `sent_args` (words), and counts it in
   * facts_derived, run_derived and facts_sent, when *sends_buffered is nonzero (the VM runs on
   * its own graph and one thread), derivations are not recorded, the frame is not negative, the
   * predicate's table is MELD_NATIVE_TABLE_BUFFERED, the destination is below *live_below and
   * both arrays have room; the send helper does it otherwise. A DERIVE likewise appends to
   * `derived` and `derived_args` (the host's fact), counted in facts_derived and run_derived, when
   * derivations are not recorded, the frame is not negative, the table is BUFFERED and both
   * arrays have room. The VM stores the derived facts when the rule run ends, in order; a rule's
   * native code may store the first ones itself before it returns (MELD_NATIVE_TABLE_PLAIN tables
   * with a free slot: the slot taken off the free list, the fact linked at the end of the node's
   * list, `live` one more, the rules over the predicate made candidates), each counted as a step
   * (steps_left), and leave the others at the front of `derived` (their arguments where they are;
   * both arrays empty when it stored them all). */
  const uint8_t* sends_buffered;
  const uint32_t* live_below;
  meld_native_array* sent; /* of meld_native_sent_fact */
  meld_native_array* sent_args;
  uint64_t* facts_sent;       /* the statistics' */
  meld_native_array* derived; /* of meld_native_sent_fact */
  meld_native_array* derived_args;
  /* A SEND of a MELD_NATIVE_TABLE_PERSISTENT_SENT predicate appends its fact to `sent_persistent`
   * (negative when the frame is: a retraction) and its arguments to `sent_args` under the same
   * conditions as a linear one's, but for the frame's sign; it counts facts_sent, and
   * facts_derived and run_derived when it is not a retraction. */
  meld_native_array* sent_persistent; /* of meld_native_sent_fact */
  const meld_native_heap* heap;       /* the heap of this VM's values (the thread's) */
  /* The global constants' values, one 8-byte word each: a GLOBAL into an unboxed register reads
   * its word (SETGLOBAL may change it meanwhile; the array itself does not move). */
  const uint64_t* globals;
  uint32_t heads_per_node;
  uint32_t rule_words;
} meld_native_context;

/* What loop_begin tells native code about an ITER or ITER_KEY loop, so that it steps through the
 * facts itself. A fact f is the 8-byte words [f * stride, (f + 1) * stride) of the predicate's
 * slot array: the high half of word 1 is its count (0: consumed), the high half of word
 * next_word links to the next fact of the loop (MELD_NATIVE_NO_FACT at the end). */
typedef struct meld_native_loop {
  meld_native_slot* slots;      /* the frame's loop slots */
  const uint64_t* const* words; /* where the slot array is: it moves when the table grows */
  const uint8_t* stop;          /* nonzero: the run is stopping (the machine's flag) */
  const uint8_t* shared_stop;   /* nonzero: every thread is stopping (an atomic flag) */
  uint32_t first;               /* the loop's first fact, or MELD_NATIVE_NO_FACT */
  uint32_t stride;
  uint32_t next_word;
  uint32_t arg_offset; /* the word of a fact's first argument */
} meld_native_loop;

struct meld_native_helpers {
  uint32_t abi_version;
  /* Runs the loop instruction at pc (ITER, ITER_KEY or ITER_SORTED), calling `body` for each
   * fact it binds; returns 1 if a body fired, 2 if the run is stopping, else 0. */
  int32_t (*loop)(const meld_native_helpers* h, meld_native_vm* vm, meld_native_frame* f, uint32_t pc,
                  meld_native_block body);
  /* steps[OPCODE] runs the straight-on instruction at pc, which has that opcode (every opcode that
   * neither jumps nor ends a block has one): no dispatch on the opcode at run time. */
  const meld_native_step* steps;
  /* TEST at pc: 1 if the field equals the register. */
  int32_t (*test)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc);
  /* FIRE or CFIRE, for each slot from its first one on that a loop of the block may consume:
   * consumes the slot's linear fact if its loop consumes and the fact is not consumed yet (native
   * code may skip the call when it sees that nothing is to be done). */
  void (*consume)(meld_native_vm* vm, meld_native_frame* f, uint32_t slot);
  /* RET_IF_UPDATED: 1 if an UPDATE ran in this frame. */
  int32_t (*updated)(meld_native_frame* f);
  /* The arguments of the fact bound to loop slot `slot` (8 bytes each, home excluded), valid until
   * the next instruction that stores a fact: LOAD into an unboxed register reads them directly. */
  const uint64_t* (*slot_args)(meld_native_vm* vm, meld_native_frame* f, uint32_t slot);
  /* Drops a reference to a boxed value of type `type` the slow way (native code counts references
   * itself: a boxed value points at its 32-bit count; this is for when it would reach zero, or
   * when the count's top bit says the value is shared between threads and changes atomically). */
  void (*release_last)(meld_native_vm* vm, uint32_t type, uint64_t value);
  /* ITER or ITER_KEY at pc: binds its slot's predicate and node, counts the loop and fills `out`;
   * native code then binds each fact to slots[slot].fact and runs the body itself, and at the
   * loop's end adds the facts it visited to *facts_tried and unbinds the slot (its fact is
   * MELD_NATIVE_NO_FACT). Native code begins an ITER at the host itself, from meld_native_context,
   * and an ITER_KEY whose argument has an `integer` index, and calls this for the other ITER_KEY
   * loops, thread facts and the step at the limit. */
  void (*loop_begin)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc, meld_native_loop* out);
  /* builtins[ID] runs the built-in function with that id of builtins.def: CALL calls it directly. */
  const meld_native_builtin* builtins;
  /* DERIVE, SEND and UPDATE at pc, their arguments gathered by native code (`args`: the
   * registers' values in the instruction's order): what the interpreter's case does once it has
   * gathered them. `pred` the predicate, `dest` the node a fact is sent to, `slot` the loop slot
   * of the fact UPDATE changes, `move_to_back` its flag kUpdateMoveToBack. */
  void (*derive)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc, uint32_t pred, const uint64_t* args);
  void (*send)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc, uint32_t pred, uint32_t dest,
               const uint64_t* args);
  void (*update)(meld_native_vm* vm, meld_native_frame* f, uint32_t pc, uint32_t slot, uint32_t move_to_back,
                 const uint64_t* args);
};

/* What a native shared object (`meldc --emit=native`) exports: meld_native_program() returns its
 * description. The program's tables travel as its bytecode (verified again when loaded); block k
 * of meldvm::nativeCodeBlocks runs blocks[k]. */
#define MELD_NATIVE_MAGIC 0x4e444c4du /* "MLDN" */
typedef struct meld_native_program_desc {
  uint32_t magic;
  uint32_t abi_version;      /* MELD_NATIVE_ABI_VERSION it was built for */
  uint32_t bytecode_version; /* meldvm::kBytecodeVersion of the bytecode below */
  uint32_t block_count;
  const uint8_t* bytecode;
  uint64_t bytecode_size;
  const meld_native_block* blocks;
} meld_native_program_desc;

#define MELD_NATIVE_ENTRY "meld_native_program"
typedef const meld_native_program_desc* (*meld_native_entry)(void);

#ifdef __cplusplus
}
#endif

#endif /* MELDVM_NATIVE_ABI_H */
