/*
 * wave_polling — the wave of wave_events.c written as a loop that waits (blockcode_polling.h):
 * each block's `wave_main` runs as a coroutine, resumed by the events it waits for. Same trace of
 * messages, sends and colours as the event-style program.
 */
#include <stdint.h>
#include <string.h>

#include "simcore/blockcode_polling.h"

static const uint32_t kColors[6] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x0000FF, 0x800080};

static void wave_main(vs_ctx* c) {
  uint32_t hop = 0;
  if (c->block != 0) {
    vs_event ev;
    do vs_wait_message(c, VS_FOREVER, &ev);
    while (ev.size != sizeof hop);
    memcpy(&hop, ev.data, sizeof hop);
  }
  vs_set_color(c, kColors[hop % 6]);
  vs_sleep(c, 100 * VS_MS); /* think, then pass it on */
  const uint32_t next = hop + 1;
  vs_send_all(c, &next, sizeof next, 0);
  /* Done: later copies of the wave are ignored. */
}

static const vs_polling_program wave_program = {"wave-polling", wave_main, 0, 0, 0, 0, NULL};
static vs_blockcode wave_code;

const vs_blockcode* vs_blockcode_entry(void) {
  vs_polling_blockcode(&wave_program, &wave_code);
  return &wave_code;
}
