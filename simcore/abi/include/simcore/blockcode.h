/*
 * blockcode.h — the block ABI: the one C interface between the simulator and a block program.
 *
 * A block program (a C BlockCode, the Meld VM, natively compiled Meld) is a table of callbacks that
 * the host calls, plus the host services it may call back. The host cannot tell block programs
 * apart, and a block program cannot see the simulator's internals.
 *
 * Loading: a shared object exports `const vs_blockcode *vs_blockcode_entry(void)`. The host checks
 * `abi_version`, allocates `state_size` zeroed bytes per block (contiguous, owned by the host, never
 * moved during a run; aligned to 16 bytes, or to `state_size` rounded up to a power of two when that
 * is smaller — enough for any C struct of that size) and calls `start` once per block at time 0,
 * before any other event of that block, then `event` for
 * every event addressed to that block. Callbacks of one simulation run on one thread, one at a time.
 *
 * Time is simulated time: a signed 64-bit count of nanoseconds (vs_time). All host services take the
 * `vs_ctx *` the callback received; it is valid only for the duration of that callback.
 */
#ifndef SIMCORE_BLOCKCODE_H
#define SIMCORE_BLOCKCODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VS_ABI_VERSION 3
/* The oldest version the host still loads: a program of version 2 simply never calls the services
 * added since (mobile_above, air_jet) and gets no VS_EV_MOBILE it does not ask for. */
#define VS_ABI_OLDEST_VERSION 2
/* Whether a host of this header runs a program built for block ABI `version`. */
static inline int vs_abi_supported(uint32_t version) {
  return version >= VS_ABI_OLDEST_VERSION && version <= VS_ABI_VERSION;
}

typedef int64_t vs_time; /* simulated nanoseconds */
typedef uint32_t vs_block_id;

#define VS_NS ((vs_time)1)
#define VS_US ((vs_time)1000)
#define VS_MS ((vs_time)1000000)
#define VS_S ((vs_time)1000000000)

#define VS_NO_BLOCK ((vs_block_id)0xFFFFFFFFu)
#define VS_MAX_MESSAGE_SIZE 65536u

/* Return codes of host services. Zero is success; errors are negative. */
enum vs_status {
  VS_OK = 0,
  VS_ERR_NO_NEIGHBOR = -1,   /* nothing is attached on that face (move: no neighbor to pivot on) */
  VS_ERR_BAD_FACE = -2,      /* face number outside [0, face_count) */
  VS_ERR_CELL_OCCUPIED = -3, /* motion target cell (or a cell it sweeps) is occupied or reserved */
  VS_ERR_OUT_OF_WORLD = -4,  /* motion target cell is outside the grid */
  VS_ERR_UNSUPPORTED = -5,   /* this target cannot do that (e.g. move a Blinky Block) */
  VS_ERR_BUSY = -6,          /* the block is already moving */
  VS_ERR_TOO_LARGE = -7,     /* message larger than VS_MAX_MESSAGE_SIZE */
  VS_ERR_BAD_ARGUMENT = -8,  /* negative delay, null pointer with non-zero size, ... */
  VS_ERR_NOT_FOUND = -9,     /* timer id unknown or already fired */
  VS_ERR_UNSTABLE = -10      /* the motion would leave the structure unstable (vsim --refuse-unstable) */
};

/* Kinds of events delivered to `event`. */
enum vs_event_kind {
  VS_EV_MESSAGE = 1,          /* a message arrived on `face` from `other`: data/size */
  VS_EV_NEIGHBOR_ADDED = 2,   /* `other` is now attached on `face` */
  VS_EV_NEIGHBOR_REMOVED = 3, /* `other` left `face` */
  VS_EV_TAP = 4,              /* the block was tapped (Blinky Blocks) */
  VS_EV_TIMER = 5,            /* a timer set with vs_host_api.set_timer fired: timer_id, tag */
  VS_EV_MOTION_END = 6,       /* the motion started by `move` ended; the block is at its new cell */
  VS_EV_SENSOR = 7,           /* a sensor reading changed: sensor, values[0..2] */
  VS_EV_MOBILE = 8            /* a mobile came over the block (values[1] = 1) or left it (0); values[0]:
                                 the mobile (Smart Blocks with physics; since ABI 3) */
};

enum vs_sensor { VS_SENSOR_ACCEL = 1 };

typedef struct vs_event {
  int kind;          /* enum vs_event_kind */
  int face;          /* MESSAGE, NEIGHBOR_*: the local face; otherwise -1 */
  vs_block_id other; /* MESSAGE: the sender; NEIGHBOR_*: the neighbor; otherwise VS_NO_BLOCK */
  const void* data;  /* MESSAGE: payload (valid during the callback only) */
  uint32_t size;     /* MESSAGE: payload size in bytes */
  uint64_t timer_id; /* TIMER: the id set_timer returned, or 0 if none was asked for */
  uint64_t tag;      /* TIMER: the tag given to set_timer */
  int sensor;        /* SENSOR: enum vs_sensor */
  int32_t values[3]; /* SENSOR: reading (ACCEL: x, y, z) */
} vs_event;

typedef struct vs_ctx vs_ctx;
typedef struct vs_host_api vs_host_api;

/* What a callback receives: the host services, the block it runs on and that block's state. */
struct vs_ctx {
  const vs_host_api* api;
  void* host;        /* opaque to the block program */
  vs_block_id block; /* the block this callback runs on */
  void* state;       /* this block's `state_size` bytes, zeroed before `start` */
  void* user;        /* the program's vs_blockcode.user (since ABI 2) */
};

/* Host services. Every function is always present (never NULL). */
struct vs_host_api {
  uint32_t abi_version;
  /* Current simulated time. */
  vs_time (*now)(vs_ctx* ctx);
  /* Number of faces (interfaces) of this target: 4 Smart Blocks, 6 Blinky Blocks, ... */
  int (*face_count)(vs_ctx* ctx);
  /* Queue a message on `face`, handed to the link after `delay` ns. Each face is a FIFO: the
   * message is transmitted after the ones queued before it, taking size*8/rate seconds, then
   * arrives after the link latency. The payload is copied. VS_ERR_NO_NEIGHBOR if the face is free.
   * A message in flight when the link breaks is dropped (and counted by the host). */
  int (*send)(vs_ctx* ctx, int face, const void* data, uint32_t size, vs_time delay);
  /* `send` on every face that has a neighbor; returns the number of messages queued (>= 0). */
  int (*send_all)(vs_ctx* ctx, const void* data, uint32_t size, vs_time delay);
  /* Fire a VS_EV_TIMER event after `delay` ns carrying `tag`. If `timer_id` is not NULL, it receives
   * a non-zero id usable with cancel_timer; ask for one only when you may cancel: timers without an
   * id cost the host no bookkeeping (their event reports timer_id 0). */
  int (*set_timer)(vs_ctx* ctx, vs_time delay, uint64_t tag, uint64_t* timer_id);
  /* Cancel a pending timer. VS_ERR_NOT_FOUND if it already fired or was cancelled. */
  int (*cancel_timer)(vs_ctx* ctx, uint64_t timer_id);
  /* Set the block's color as 0xRRGGBB. */
  int (*set_color)(vs_ctx* ctx, uint32_t rgb);
  uint32_t (*color)(vs_ctx* ctx);
  /* Set the value the block displays (Smart Blocks). */
  int (*set_value)(vs_ctx* ctx, int32_t value);
  /* Start a motion into the adjacent cell behind `face`: a translation (Smart Blocks), or whatever
   * the target's motion rule makes of it (Catoms 2D: a 60-degree roll around a neighbor; Catoms 3D:
   * a 60-degree rotation over a neighbor's surface; see targets/README.md). The destination, and
   * any cell swept on the way, is reserved at once; links break now and form again when
   * VS_EV_MOTION_END arrives. Errors: VS_ERR_UNSUPPORTED (the target cannot move: Blinky Blocks),
   * VS_ERR_BUSY, VS_ERR_CELL_OCCUPIED, VS_ERR_OUT_OF_WORLD, VS_ERR_BAD_FACE, VS_ERR_NO_NEIGHBOR (no
   * neighbor to pivot on), VS_ERR_UNSTABLE (refused by the reality checker). */
  int (*move)(vs_ctx* ctx, int face);
  /* The block attached on `face`, or VS_NO_BLOCK. */
  vs_block_id (*neighbor)(vs_ctx* ctx, int face);
  int (*neighbor_count)(vs_ctx* ctx);
  /* Lattice cell of the block (the destination cell while moving). */
  void (*position)(vs_ctx* ctx, int32_t xyz[3]);
  /* Latest reading of a sensor into values[0..2]; VS_ERR_UNSUPPORTED if the target has none. */
  int (*read_sensor)(vs_ctx* ctx, int sensor, int32_t values[3]);
  /* Random numbers from this block's own stream, derived from (seed, block id). */
  uint32_t (*random_u32)(vs_ctx* ctx);
  /* Uniform in [0, bound) without bias; bound > 0. */
  uint32_t (*random_below)(vs_ctx* ctx, uint32_t bound);
  /* Append a line to the run's trace (shown when the trace filter selects this block). */
  void (*trace)(vs_ctx* ctx, const char* text);
  /* Number of blocks in the world. */
  uint32_t (*block_count)(vs_ctx* ctx);
  /* The face of this block whose adjacent cell is `xyz` (e.g. to turn a target cell into a `move`),
   * or VS_ERR_BAD_ARGUMENT when `xyz` is not an adjacent cell (since ABI 2). */
  int (*face_toward)(vs_ctx* ctx, const int32_t xyz[3]);
  /* Since ABI 3 (Smart Blocks with mobiles, simcore/physics.hpp). The mobile over this block: its
   * number in *mobile and its centre and angle in xy_angle (mm on the surface, degrees); or
   * VS_ERR_NOT_FOUND when none covers the block's centre, VS_ERR_UNSUPPORTED without physics. */
  int (*mobile_above)(vs_ctx* ctx, int32_t* mobile, double xy_angle[3]);
  /* Blow this block's jet towards `face` at `power` (0..1) for `duration` ns: it pushes a mobile
   * over or next to the block that way. A new command replaces the jet's last one; power 0 closes
   * it. VS_ERR_BAD_FACE, VS_ERR_BAD_ARGUMENT (power outside 0..1, negative duration),
   * VS_ERR_UNSUPPORTED without physics. */
  int (*air_jet)(vs_ctx* ctx, int face, double power, vs_time duration);
};

/* The table a block program exports. Callbacks may be NULL where the program has nothing to do. */
typedef struct vs_blockcode {
  uint32_t abi_version; /* VS_ABI_VERSION */
  const char* name;     /* short name for logs */
  uint32_t state_size;  /* bytes of per-block state allocated by the host */
  void (*start)(vs_ctx* ctx);
  void (*event)(vs_ctx* ctx, const vs_event* event);
  /* Write a one-line description of the block's state for the IDE (NUL-terminated, truncated to
   * `capacity`). Returns the length it would have written. */
  int (*info)(vs_ctx* ctx, char* text, size_t capacity);
  /* Program-wide data handed to every callback as ctx->user (since ABI 2): lets one program object
   * serve all blocks, e.g. the Meld VM's shared code and fact store. NULL for most C BlockCodes. */
  void* user;
} vs_blockcode;

/* Symbol a block program shared object exports. */
#define VS_BLOCKCODE_ENTRY_SYMBOL "vs_blockcode_entry"
typedef const vs_blockcode* (*vs_blockcode_entry_fn)(void);

/* Convenience wrappers, so block programs read naturally. */
static inline vs_time vs_now(vs_ctx* c) { return c->api->now(c); }
static inline int vs_send(vs_ctx* c, int face, const void* d, uint32_t n, vs_time delay) {
  return c->api->send(c, face, d, n, delay);
}
static inline int vs_send_all(vs_ctx* c, const void* d, uint32_t n, vs_time delay) {
  return c->api->send_all(c, d, n, delay);
}
static inline int vs_set_timer(vs_ctx* c, vs_time delay, uint64_t tag) {
  return c->api->set_timer(c, delay, tag, NULL);
}
static inline int vs_set_color(vs_ctx* c, uint32_t rgb) { return c->api->set_color(c, rgb); }
static inline int vs_move(vs_ctx* c, int face) { return c->api->move(c, face); }
static inline uint32_t vs_random_below(vs_ctx* c, uint32_t bound) { return c->api->random_below(c, bound); }

#ifdef __cplusplus
}
#endif

#endif /* SIMCORE_BLOCKCODE_H */
