/*
 * wave_events — a wave from block 0, written in the event style of the block ABI (blockcode.h).
 * wave_polling.c is the same program written as a loop that waits (blockcode_polling.h); both give
 * the same trace of messages, sends and colours (tests/cli: cli.polling-wave).
 *
 * Block 0 starts the wave at time 0 with hop 0. A block that hears of the wave for the first time
 * (a 4-byte hop count h) takes the colour of h (red, orange, yellow, green, blue, purple, then
 * again), thinks for 100 ms, and sends h + 1 to all its neighbours; it ignores later copies.
 */
#include <stdint.h>
#include <string.h>

#include "simcore/blockcode.h"

static const uint32_t kColors[6] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x0000FF, 0x800080};

typedef struct wave_state {
  uint32_t hop;
  uint8_t reached;
} wave_state;

static void reach(vs_ctx* c, uint32_t hop) {
  wave_state* s = (wave_state*)c->state;
  s->reached = 1;
  s->hop = hop;
  vs_set_color(c, kColors[hop % 6]);
  vs_set_timer(c, 100 * VS_MS, 0); /* think, then pass it on */
}

static void on_start(vs_ctx* c) {
  if (c->block == 0) reach(c, 0);
}

static void on_event(vs_ctx* c, const vs_event* ev) {
  wave_state* s = (wave_state*)c->state;
  if (ev->kind == VS_EV_MESSAGE && !s->reached && ev->size == sizeof(uint32_t)) {
    uint32_t hop;
    memcpy(&hop, ev->data, sizeof hop);
    reach(c, hop);
  } else if (ev->kind == VS_EV_TIMER) {
    const uint32_t next = s->hop + 1;
    vs_send_all(c, &next, sizeof next, 0);
  }
}

static const vs_blockcode wave_code = {
    VS_ABI_VERSION, "wave-events", sizeof(wave_state), on_start, on_event, NULL, NULL,
};

const vs_blockcode* vs_blockcode_entry(void) { return &wave_code; }
