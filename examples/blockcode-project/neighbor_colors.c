/*
 * neighbor_colors — a BlockCode built outside the toolchain's tree (see README.md).
 *
 * Each block shows how many neighbours it has (1 red, 2 orange, 3 yellow, 4 green, 5 blue,
 * 6 white; alone: grey) and keeps that colour up to date as neighbours come and go. A tap makes
 * the block flash three times (a timer every 200 ms) before it shows its count again.
 */
#include <stdint.h>
#include <stdio.h>

#include "simcore/blockcode.h"

static const uint32_t kByCount[7] = {0x808080, 0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x0000FF, 0xFFFFFF};
static const vs_time kFlashPeriod = 200000000; /* ns */

typedef struct block_state {
  uint32_t flashes_left; /* colour changes still to show after a tap */
} block_state;

static void show_count(vs_ctx* c) {
  int n = c->api->neighbor_count(c);
  vs_set_color(c, kByCount[n < 0 ? 0 : n > 6 ? 6 : n]);
}

static void on_start(vs_ctx* c) { show_count(c); }

static void on_event(vs_ctx* c, const vs_event* ev) {
  block_state* s = (block_state*)c->state;
  switch (ev->kind) {
    case VS_EV_NEIGHBOR_ADDED:
    case VS_EV_NEIGHBOR_REMOVED:
      if (s->flashes_left == 0) show_count(c);
      break;
    case VS_EV_TAP:
      if (s->flashes_left == 0) c->api->set_timer(c, kFlashPeriod, 0, NULL);
      s->flashes_left = 6;
      vs_set_color(c, 0xFFFFFF);
      break;
    case VS_EV_TIMER:
      if (--s->flashes_left == 0) {
        show_count(c);
      } else {
        if (s->flashes_left % 2 == 0) vs_set_color(c, 0xFFFFFF);
        else show_count(c);
        c->api->set_timer(c, kFlashPeriod, 0, NULL);
      }
      break;
    default:
      break;
  }
}

static int on_info(vs_ctx* c, char* text, size_t capacity) {
  return snprintf(text, capacity, "%d neighbours", c->api->neighbor_count(c));
}

static const vs_blockcode neighbor_colors_code = {
    VS_ABI_VERSION, "neighbor-colors", sizeof(block_state), on_start, on_event, on_info, NULL,
};

const vs_blockcode* vs_blockcode_entry(void) { return &neighbor_colors_code; }
