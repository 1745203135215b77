/*
 * color_flood — a flood that colors every block by its hop distance from where the flood started
 * (Blinky Blocks, any static world; also runs on Smart Blocks).
 *
 * Block 0 starts wave 1 at t = 0. Tapping a block starts a new wave from that block. A flood message
 * carries (wave, origin, hops). A block adopts a message when its wave is newer than the one it
 * knows, or when it is the same wave with fewer hops — messages do not always arrive along shortest
 * paths first (a face's queue may delay one), so a later, shorter path corrects the color. On
 * adopting it shows palette[hops % 10] (and the hop count on targets with a display) and
 * forwards (wave, origin, hops + 1) to all its neighbors.
 * Once the queue is empty every reached block shows its distance; the run ends on its own.
 *
 * Waves are ordered by (wave number, origin id): two taps at the same time on different blocks
 * pick the same number, and the origin breaks the tie the same way on every block.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "simcore/blockcode.h"

/* Hop distance 0, 1, 2, ...: red, orange, yellow, green, cyan, blue, purple, magenta, pink, white. */
static const uint32_t kPalette[10] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x00FFFF,
                                      0x0000FF, 0x800080, 0xFF00FF, 0xFFC0CB, 0xFFFFFF};

typedef struct flood_msg {
  uint32_t wave;
  uint32_t origin;
  uint32_t hops;
} flood_msg;

typedef struct flood_state {
  uint32_t wave; /* 0 = not reached yet */
  uint32_t origin;
  uint32_t hops;
} flood_state;

static int newer(const flood_msg* m, const flood_state* s) {
  if (m->wave != s->wave) return m->wave > s->wave;
  if (m->origin != s->origin) return m->origin > s->origin;
  return m->hops < s->hops;
}

static void adopt(vs_ctx* c, const flood_msg* m) {
  flood_state* s = (flood_state*)c->state;
  s->wave = m->wave;
  s->origin = m->origin;
  s->hops = m->hops;
  vs_set_color(c, kPalette[m->hops % 10]);
  c->api->set_value(c, (int32_t)m->hops); /* Smart Blocks show the distance; others say unsupported */
  flood_msg next = *m;
  next.hops = m->hops + 1;
  vs_send_all(c, &next, sizeof next, 0);
}

static void start_wave(vs_ctx* c) {
  const flood_state* s = (const flood_state*)c->state;
  flood_msg m = {s->wave + 1, c->block, 0};
  char line[64];
  snprintf(line, sizeof line, "wave %u starts here", (unsigned)m.wave);
  c->api->trace(c, line);
  adopt(c, &m);
}

static void on_start(vs_ctx* c) {
  if (c->block == 0) start_wave(c);
}

static void on_event(vs_ctx* c, const vs_event* ev) {
  flood_state* s = (flood_state*)c->state;
  if (ev->kind == VS_EV_TAP) {
    start_wave(c);
  } else if (ev->kind == VS_EV_MESSAGE && ev->size == sizeof(flood_msg)) {
    flood_msg m;
    memcpy(&m, ev->data, sizeof m);
    if (newer(&m, s)) adopt(c, &m);
  } else if (ev->kind == VS_EV_NEIGHBOR_ADDED && s->wave != 0) {
    /* A newcomer (worlds that change) learns the current wave from us. */
    flood_msg m = {s->wave, s->origin, s->hops + 1};
    vs_send(c, ev->face, &m, sizeof m, 0);
  }
}

static int on_info(vs_ctx* c, char* text, size_t capacity) {
  const flood_state* s = (const flood_state*)c->state;
  if (s->wave == 0) return snprintf(text, capacity, "not reached");
  return snprintf(text, capacity, "wave %u from #%u, %u hops", (unsigned)s->wave, (unsigned)s->origin,
                  (unsigned)s->hops);
}

static const vs_blockcode color_flood_code = {
    VS_ABI_VERSION, "color-flood", sizeof(flood_state), on_start, on_event, on_info, NULL,
};

const vs_blockcode* vs_blockcode_entry(void) { return &color_flood_code; }
