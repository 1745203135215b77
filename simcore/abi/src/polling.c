/*
 * The coroutines behind blockcode_polling.h. Each block's state holds, in this order: the stack
 * (guard words at its low end), the coroutine record, the inbox (entries, then message bytes) and
 * the program's own state. The stack grows down, away from the block's own record: an overflow
 * that passes the guard words leaves the record whole, so the block can still be switched back from
 * and the overflow reported. The host calls `start` and `event` as for any block program; they switch to the block's
 * stack, and the block's waits switch back. Nothing here is shared between blocks or programs:
 * the program is found through ctx->user, the block's record through ctx->state.
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context_switch.h"
#include "simcore/blockcode_polling.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define VS_ASAN 1
#else
#define VS_ASAN 0
#endif

/* Tags of the timers behind vs_sleep and timeouts ("pollwait"): a program's own timers keep theirs. */
#define TIMEOUT_TAG 0x706F6C6C77616974ull
#define GUARD_WORD 0x5A17C0DE5A17C0DEull
#define GUARD_WORDS 4

typedef struct inbox_entry {
  vs_event ev;
  uint32_t offset; /* of its data in the inbox bytes */
} inbox_entry;

typedef struct coroutine {
  vs_ctx ctx; /* the one main gets: api/host refreshed at each resume, state = the program's */
  vs_co_context co, host;
  const vs_event* delivered; /* what resumed the block (NULL: its timeout) */
  uint64_t timeout_id;       /* cancellable timeout pending (0: none) */
  uint32_t waiting_kinds;    /* while suspended in a wait; 0 otherwise */
  int waiting_sensor;        /* for VS_EV_SENSOR: the sensor wanted (0: any) */
  uint8_t timeout_pending, done, drop_reported;
  uint32_t dropped;
  uint32_t inbox_count, inbox_bytes_used;
  int32_t lent; /* inbox entry returned by the last wait, removed at the next (-1: none) */
#if VS_ASAN
  void* asan_host_fake;
  void* asan_co_fake;
  const void* host_stack_bottom;
  size_t host_stack_size;
#endif
} coroutine;

/* Where things are in a block's state, from the program's figures. */
typedef struct layout {
  uint32_t events, bytes, stack;
  size_t co, inbox, inbox_data, user, total; /* offsets in the state; the stack is at 0 */
} layout;

static size_t align16(size_t n) { return (n + 15u) & ~(size_t)15u; }

static layout layout_of(const vs_polling_program* p) {
  layout l;
  l.events = p->inbox_events ? p->inbox_events : VS_POLLING_DEFAULT_INBOX_EVENTS;
  l.bytes = p->inbox_bytes ? p->inbox_bytes : VS_POLLING_DEFAULT_INBOX_BYTES;
  l.stack = p->stack_size ? (uint32_t)align16(p->stack_size) : VS_POLLING_DEFAULT_STACK;
  l.co = l.stack;
  l.inbox = l.co + align16(sizeof(coroutine));
  l.inbox_data = l.inbox + align16((size_t)l.events * sizeof(inbox_entry));
  l.user = l.inbox_data + align16(l.bytes);
  l.total = l.user + align16(p->state_size);
  return l;
}

static const vs_polling_program* program_of(const vs_ctx* c) { return (const vs_polling_program*)c->user; }
static coroutine* coroutine_of(vs_ctx* c) { return (coroutine*)((char*)c - offsetof(coroutine, ctx)); }
/* Everything is found from the record: the state starts l->co bytes before it. */
static char* state_of(coroutine* co, const layout* l) { return (char*)co - l->co; }
static inbox_entry* entries(coroutine* co, const layout* l) { return (inbox_entry*)(state_of(co, l) + l->inbox); }
static uint8_t* inbox_data(coroutine* co, const layout* l) { return (uint8_t*)state_of(co, l) + l->inbox_data; }
static uint64_t* guard(coroutine* co, const layout* l) { return (uint64_t*)state_of(co, l); }

static void check_guard(coroutine* co, const layout* l) {
  const uint64_t* g = guard(co, l);
  for (int i = 0; i < GUARD_WORDS; ++i)
    if (g[i] != GUARD_WORD) {
      fprintf(stderr,
              "vs_polling: block %u of program '%s' overflowed its %u-byte stack: raise "
              "vs_polling_program.stack_size\n",
              (unsigned)co->ctx.block, program_of(&co->ctx)->name, (unsigned)l->stack);
      abort();
    }
}

/* --- switching --------------------------------------------------------------------------- */

static void to_block(coroutine* co, const layout* l) {
#if VS_ASAN
  __sanitizer_start_switch_fiber(&co->asan_host_fake, state_of(co, l), l->stack);
#endif
  vs_co_switch(&co->host, &co->co);
#if VS_ASAN
  __sanitizer_finish_switch_fiber(co->asan_host_fake, NULL, NULL);
#endif
  check_guard(co, l);
}

static void to_host(coroutine* co, int finished) {
#if VS_ASAN
  __sanitizer_start_switch_fiber(finished ? NULL : &co->asan_co_fake, co->host_stack_bottom, co->host_stack_size);
#else
  (void)finished;
#endif
  vs_co_switch(&co->co, &co->host);
#if VS_ASAN
  __sanitizer_finish_switch_fiber(co->asan_co_fake, &co->host_stack_bottom, &co->host_stack_size);
#endif
}

static void block_entry(void* arg) {
  coroutine* co = (coroutine*)arg;
#if VS_ASAN
  __sanitizer_finish_switch_fiber(NULL, &co->host_stack_bottom, &co->host_stack_size);
#endif
  program_of(&co->ctx)->main(&co->ctx);
  co->done = 1;
  to_host(co, 1);
  abort(); /* a finished block is never resumed */
}

/* --- the inbox --------------------------------------------------------------------------- */

static int accepts(uint32_t kinds, int sensor, const vs_event* ev) {
  if (ev->kind <= 0 || ev->kind >= 16 || !(kinds & VS_WAIT_KIND(ev->kind))) return 0;
  return ev->kind != VS_EV_SENSOR || sensor == 0 || ev->sensor == sensor;
}

static void release_lent(coroutine* co, const layout* l) {
  if (co->lent < 0) return;
  inbox_entry* e = entries(co, l);
  uint8_t* data = inbox_data(co, l);
  const uint32_t i = (uint32_t)co->lent, size = e[i].ev.size, offset = e[i].offset;
  co->lent = -1;
  if (size) {
    memmove(data + offset, data + offset + size, co->inbox_bytes_used - offset - size);
    co->inbox_bytes_used -= size;
    for (uint32_t k = 0; k < co->inbox_count; ++k)
      if (k != i && e[k].ev.size && e[k].offset > offset) e[k].offset -= size;
  }
  memmove(&e[i], &e[i + 1], (co->inbox_count - i - 1) * sizeof(inbox_entry));
  --co->inbox_count;
}

static void keep(coroutine* co, const layout* l, vs_ctx* host_ctx, const vs_event* ev) {
  if (co->inbox_count == l->events || ev->size > l->bytes - co->inbox_bytes_used) {
    ++co->dropped;
    if (!co->drop_reported) {
      co->drop_reported = 1;
      char line[160];
      snprintf(line, sizeof line, "vs_polling: inbox full (%u events, %u bytes): an event of kind %d was dropped",
               (unsigned)l->events, (unsigned)l->bytes, ev->kind);
      host_ctx->api->trace(host_ctx, line);
    }
    return;
  }
  inbox_entry* e = &entries(co, l)[co->inbox_count++];
  e->ev = *ev;
  e->offset = co->inbox_bytes_used;
  e->ev.data = NULL;
  if (ev->size) {
    memcpy(inbox_data(co, l) + co->inbox_bytes_used, ev->data, ev->size);
    co->inbox_bytes_used += ev->size;
  }
}

/* --- the callbacks the host sees ---------------------------------------------------------- */

static void refresh(coroutine* co, const vs_ctx* c) {
  co->ctx.api = c->api;
  co->ctx.host = c->host;
  co->ctx.block = c->block;
  co->ctx.user = c->user;
}

static coroutine* record_of(vs_ctx* c, const layout* l) { return (coroutine*)((char*)c->state + l->co); }

static void on_start(vs_ctx* c) {
  const layout l = layout_of(program_of(c));
  coroutine* co = record_of(c, &l);
  refresh(co, c);
  co->ctx.state = (char*)c->state + l.user;
  co->lent = -1;
  uint64_t* g = guard(co, &l);
  for (int i = 0; i < GUARD_WORDS; ++i) g[i] = GUARD_WORD;
  vs_co_make(&co->co, (char*)c->state + GUARD_WORDS * sizeof(uint64_t), l.stack - GUARD_WORDS * sizeof(uint64_t),
             block_entry, co);
  to_block(co, &l);
}

static void on_event(vs_ctx* c, const vs_event* ev) {
  const layout l = layout_of(program_of(c));
  coroutine* co = record_of(c, &l);
  if (co->done) return;  // (the ABI promises `start` before any event)
  refresh(co, c);
  if (ev->kind == VS_EV_TIMER && ev->tag == TIMEOUT_TAG) {
    /* Ours: the pending timeout (cancelled ones never fire). */
    if (!co->timeout_pending || ev->timer_id != co->timeout_id) return;
    co->timeout_pending = 0;
    co->timeout_id = 0;
    co->delivered = NULL;
    to_block(co, &l);
    return;
  }
  if (co->waiting_kinds && accepts(co->waiting_kinds, co->waiting_sensor, ev)) {
    if (co->timeout_pending && co->timeout_id) c->api->cancel_timer(c, co->timeout_id);
    co->timeout_pending = 0;
    co->timeout_id = 0;
    co->delivered = ev;
    to_block(co, &l);
    return;
  }
  keep(co, &l, c, ev);
}

static int on_info(vs_ctx* c, char* text, size_t capacity) {
  const vs_polling_program* p = program_of(c);
  const layout l = layout_of(p);
  coroutine* co = record_of(c, &l);
  if (p->info) {
    refresh(co, c);
    return p->info(&co->ctx, text, capacity);
  }
  return snprintf(text, capacity, "%s, %u in the inbox", co->done ? "done" : co->waiting_kinds ? "waiting" : "asleep",
                  (unsigned)co->inbox_count);
}

void vs_polling_blockcode(const vs_polling_program* program, vs_blockcode* table) {
  const layout l = layout_of(program);
  memset(table, 0, sizeof *table);
  table->abi_version = VS_ABI_VERSION;
  table->name = program->name;
  table->state_size = (uint32_t)l.total;
  table->start = on_start;
  table->event = on_event;
  table->info = on_info;
  table->user = (void*)program;
}

/* --- what main calls ------------------------------------------------------------------------ */

static int wait_for(vs_ctx* c, uint32_t kinds, int sensor, vs_time timeout, vs_event* ev) {
  coroutine* co = coroutine_of(c);
  const layout l = layout_of(program_of(c));
  release_lent(co, &l);
  if (kinds) {
    inbox_entry* e = entries(co, &l);
    for (uint32_t i = 0; i < co->inbox_count; ++i)
      if (accepts(kinds, sensor, &e[i].ev)) {
        *ev = e[i].ev;
        if (ev->size) ev->data = inbox_data(co, &l) + e[i].offset;
        co->lent = (int32_t)i;
        return VS_OK;
      }
  }
  if (timeout == 0) return VS_WAIT_TIMEOUT;
  if (timeout > 0) {
    /* A sleep needs no id (nothing ends it early); a timeout may be cancelled. */
    co->timeout_id = 0;
    const int rc = c->api->set_timer(c, timeout, TIMEOUT_TAG, kinds ? &co->timeout_id : NULL);
    if (rc != VS_OK) return rc;
    co->timeout_pending = 1;
  }
  co->waiting_kinds = kinds;
  co->waiting_sensor = sensor;
  to_host(co, 0);
  co->waiting_kinds = 0;
  if (!co->delivered) return VS_WAIT_TIMEOUT;
  *ev = *co->delivered;
  co->delivered = NULL;
  return VS_OK;
}

int vs_wait(vs_ctx* c, uint32_t kinds, vs_time timeout, vs_event* ev) {
  if (!c || !ev || !(kinds & VS_WAIT_ANY) || (timeout < 0 && timeout != VS_FOREVER)) return VS_ERR_BAD_ARGUMENT;
  return wait_for(c, kinds & VS_WAIT_ANY, 0, timeout, ev);
}

int vs_wait_message(vs_ctx* c, vs_time timeout, vs_event* ev) {
  return vs_wait(c, VS_WAIT_KIND(VS_EV_MESSAGE), timeout, ev);
}

int vs_wait_sensor(vs_ctx* c, int sensor, vs_time timeout, vs_event* ev) {
  if (!c || !ev || sensor <= 0 || (timeout < 0 && timeout != VS_FOREVER)) return VS_ERR_BAD_ARGUMENT;
  return wait_for(c, VS_WAIT_KIND(VS_EV_SENSOR), sensor, timeout, ev);
}

int vs_sleep(vs_ctx* c, vs_time delay) {
  if (!c || delay < 0) return VS_ERR_BAD_ARGUMENT;
  vs_event unused;
  const int rc = wait_for(c, 0, 0, delay, &unused);
  return rc == VS_WAIT_TIMEOUT ? VS_OK : rc;
}

uint32_t vs_inbox_dropped(vs_ctx* c) { return coroutine_of(c)->dropped; }
