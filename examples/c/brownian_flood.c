/*
 * brownian_flood — the block program of benchmark B1 (Smart Blocks).
 *
 * Every block wanders: it waits a random time uniform in [0, 1] s, picks one of the 4 directions at
 * random and moves there if the cell is free (a move lasts the target's motion time, 1 s), then
 * waits again. Block 0 starts a flood at t = 0: a 4-byte message to all its neighbors; a block that
 * receives it for the first time turns red and forwards it to all its current neighbors.
 * Blocks start with a wait rather than a move so that a million blocks do not all act at t = 0.
 *
 * The epidemic variant (brownian_epidemic.so, `brownian-flood --epidemic`) also tells every block
 * that becomes a neighbor of an informed one later: at half density the plain flood dies in its
 * first cluster, while the epidemic spreads by motion until every block has it.
 */
#include <stdint.h>
#include <string.h>

#include "simcore/blockcode.h"

typedef struct brownian_state {
  uint8_t flooded;
  uint8_t hops;
} brownian_state;

enum { TIMER_TRY_MOVE = 1 };

static void wait_then_try(vs_ctx* c) {
  vs_set_timer(c, (vs_time)vs_random_below(c, 1000000001u), TIMER_TRY_MOVE);
}

static void forward_flood(vs_ctx* c, uint32_t hops) {
  brownian_state* s = (brownian_state*)c->state;
  s->flooded = 1;
  s->hops = hops > 255 ? 255 : (uint8_t)hops;
  vs_set_color(c, 0xFF0000);
  uint32_t next = hops + 1;
  vs_send_all(c, &next, sizeof next, 0);
}

static void on_start(vs_ctx* c) {
  if (c->block == 0) forward_flood(c, 0);
  wait_then_try(c);
}

static void on_event(vs_ctx* c, const vs_event* ev);

static void on_event_epidemic(vs_ctx* c, const vs_event* ev) {
  const brownian_state* s = (const brownian_state*)c->state;
  if (ev->kind == VS_EV_NEIGHBOR_ADDED && s->flooded) {
    uint32_t next = (uint32_t)s->hops + 1;
    vs_send(c, ev->face, &next, sizeof next, 0);
    return;
  }
  on_event(c, ev);
}

static void on_event(vs_ctx* c, const vs_event* ev) {
  brownian_state* s = (brownian_state*)c->state;
  switch (ev->kind) {
    case VS_EV_TIMER:
      if (vs_move(c, (int)vs_random_below(c, 4)) != VS_OK) wait_then_try(c);
      break;
    case VS_EV_MOTION_END:
      wait_then_try(c);
      break;
    case VS_EV_MESSAGE:
      if (!s->flooded && ev->size == sizeof(uint32_t)) {
        uint32_t hops;
        memcpy(&hops, ev->data, sizeof hops);
        forward_flood(c, hops);
      }
      break;
    default:
      break;
  }
}

static int on_info(vs_ctx* c, char* text, size_t capacity) {
  const brownian_state* s = (const brownian_state*)c->state;
  if (!capacity) return 0;
  const char* msg = s->flooded ? "flooded" : "not reached";
  size_t n = strlen(msg);
  if (n >= capacity) n = capacity - 1;
  memcpy(text, msg, n);
  text[n] = '\0';
  return (int)strlen(msg);
}

static const vs_blockcode brownian_flood_code = {
    VS_ABI_VERSION, "brownian-flood", sizeof(brownian_state), on_start, on_event, on_info, NULL,
};
static const vs_blockcode brownian_epidemic_code = {
    VS_ABI_VERSION, "brownian-epidemic", sizeof(brownian_state), on_start, on_event_epidemic, on_info, NULL,
};

/* Either variant, for programs that link this file (the B1 benchmark). */
const vs_blockcode* brownian_flood_variant(int epidemic) {
  return epidemic ? &brownian_epidemic_code : &brownian_flood_code;
}

/* The shared object's entry: built twice, brownian_epidemic.so with BROWNIAN_EPIDEMIC=1. */
#ifndef BROWNIAN_EPIDEMIC
#define BROWNIAN_EPIDEMIC 0
#endif
const vs_blockcode* vs_blockcode_entry(void) { return brownian_flood_variant(BROWNIAN_EPIDEMIC); }
