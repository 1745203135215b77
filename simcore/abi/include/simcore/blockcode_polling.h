/*
 * blockcode_polling.h — block programs written as a loop that waits.
 *
 * The block ABI (blockcode.h) calls a program back for each event. Some programs read better as a
 * loop: wait for a message, act, sleep, send, wait again. Here each block runs such a loop, its
 * `main`, as a coroutine with its own small stack inside the block's state: a wait returns to the
 * simulator, and the event that satisfies it resumes the block where it waited. Waiting costs no
 * simulated time and no host work between events (no busy-waiting, no polling timers).
 *
 * Build: link the static library `blockcode_polling` (CMake) into the BlockCode's shared object,
 * and export the table that vs_polling_blockcode fills:
 *
 *     static void block_main(vs_ctx* c) { ... vs_wait_message(c, VS_FOREVER, &ev); ... }
 *     static const vs_polling_program program = {"my-program", block_main, sizeof(my_state)};
 *     static vs_blockcode table;
 *     const vs_blockcode* vs_blockcode_entry(void) { vs_polling_blockcode(&program, &table); return &table; }
 *
 * In `main`, `c` stays valid for the block's whole life (unlike a callback's ctx) and `c->state` is
 * the program's own `state_size` zeroed bytes. Every host service of blockcode.h may be called.
 * Events that arrive while the block waits for another kind are kept, in arrival order, in a
 * small per-block inbox, and handed to the next wait that accepts them; an event that does not
 * fit is dropped, counted, and reported once per block in the trace (raise `inbox_events` or
 * `inbox_bytes`). A block whose `main` returns is done: its later events are ignored.
 *
 * A stack that overflows `stack_size` is detected (guard words) when the block next waits:
 * the process stops with a message naming the block and the size. (Guard pages would need a memory
 * mapping per block, more than Linux allows at a hundred thousand blocks.)
 */
#ifndef SIMCORE_BLOCKCODE_POLLING_H
#define SIMCORE_BLOCKCODE_POLLING_H

#include "simcore/blockcode.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VS_FOREVER ((vs_time)-1)
#define VS_POLLING_DEFAULT_STACK 8192u
#define VS_POLLING_DEFAULT_INBOX_EVENTS 8u
#define VS_POLLING_DEFAULT_INBOX_BYTES 256u

/* Which event kinds a wait accepts: VS_WAIT_KIND(VS_EV_MESSAGE) | VS_WAIT_KIND(VS_EV_TAP) ... */
#define VS_WAIT_KIND(kind) (1u << (kind))
#define VS_WAIT_ANY 0xFFFEu

/* What a wait returns besides VS_OK: the timeout passed first. */
#define VS_WAIT_TIMEOUT 1

typedef void (*vs_block_main)(vs_ctx* ctx);

typedef struct vs_polling_program {
  const char* name;         /* short name for logs */
  vs_block_main main;       /* each block's loop, started at time 0 */
  uint32_t state_size;      /* the program's own per-block state (c->state in main) */
  uint32_t stack_size;      /* bytes of stack per block; 0: VS_POLLING_DEFAULT_STACK */
  uint32_t inbox_events;    /* events kept while waiting for others; 0: the default */
  uint32_t inbox_bytes;     /* message bytes kept with them; 0: the default */
  int (*info)(vs_ctx* ctx, char* text, size_t capacity); /* as vs_blockcode.info (c->state: yours) */
} vs_polling_program;

/* Fills `table` so that the host runs `program` (both must outlive the run: make them static). */
void vs_polling_blockcode(const vs_polling_program* program, vs_blockcode* table);

/* Waits for an event of one of `kinds` (VS_WAIT_KIND bits), for at most `timeout` ns
 * (VS_FOREVER: no limit). Returns VS_OK with the event in *ev (a message's data stays valid until
 * the next wait), VS_WAIT_TIMEOUT, or VS_ERR_BAD_ARGUMENT (no kinds, negative timeout, NULL ev). */
int vs_wait(vs_ctx* ctx, uint32_t kinds, vs_time timeout, vs_event* ev);
/* vs_wait for a message. */
int vs_wait_message(vs_ctx* ctx, vs_time timeout, vs_event* ev);
/* vs_wait for a reading of `sensor` (enum vs_sensor); other sensors' readings stay in the inbox. */
int vs_wait_sensor(vs_ctx* ctx, int sensor, vs_time timeout, vs_event* ev);
/* Waits `delay` ns of simulated time (events meanwhile go to the inbox). */
int vs_sleep(vs_ctx* ctx, vs_time delay);
/* Events dropped so far because the inbox was full. */
uint32_t vs_inbox_dropped(vs_ctx* ctx);

#ifdef __cplusplus
}
#endif

#endif
