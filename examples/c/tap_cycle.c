/*
 * tap_cycle — every tap moves a block to the next color of a 6-color cycle (Blinky Blocks).
 *
 * Blocks keep the world's colors until their first tap; the k-th tap shows kCycle[(k - 1) % 6]:
 * red, orange, yellow, green, blue, purple. Each tap also writes a trace line, so
 * `vsim --trace kinds=tap,color,trace` shows cause and effect. Taps come from the world's
 * <schedule> or from `vsim --tap ID@TIME`. No messages, no timers: the run ends after the last tap.
 */
#include <stdint.h>
#include <stdio.h>

#include "simcore/blockcode.h"

static const uint32_t kCycle[6] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x0000FF, 0x800080};
static const char* const kCycleNames[6] = {"red", "orange", "yellow", "green", "blue", "purple"};

typedef struct tap_state {
  uint32_t taps;
} tap_state;

static void on_event(vs_ctx* c, const vs_event* ev) {
  if (ev->kind != VS_EV_TAP) return;
  tap_state* s = (tap_state*)c->state;
  const uint32_t k = s->taps++ % 6;
  vs_set_color(c, kCycle[k]);
  char line[48];
  snprintf(line, sizeof line, "tap %u -> %s", (unsigned)s->taps, kCycleNames[k]);
  c->api->trace(c, line);
}

static int on_info(vs_ctx* c, char* text, size_t capacity) {
  const tap_state* s = (const tap_state*)c->state;
  return snprintf(text, capacity, "%u taps", (unsigned)s->taps);
}

static const vs_blockcode tap_cycle_code = {
    VS_ABI_VERSION, "tap-cycle", sizeof(tap_state), NULL, on_event, on_info, NULL,
};

const vs_blockcode* vs_blockcode_entry(void) { return &tap_cycle_code; }
