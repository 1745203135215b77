/*
 * conveyor — the VisibleSim paper's air-jet experiment (its Fig. 11): Smart Blocks convey a part
 * (a mobile, simcore/physics.hpp) along a broken line, each block knowing only what lies over it.
 *
 * 1. Block 0 knows the path: (75, 425) mm at 0 s, (350, 425) at 10 s, (400, 375) at 13 s,
 *    (400, 75) at 24 s. It floods the path and the start time; every block keeps them.
 * 2. A block the mobile comes over (VS_EV_MOBILE) controls it every 50 ms while it stays there:
 *    it reads the mobile's position (mobile_above), interpolates the goal at the current time,
 *    and computes the force the mobile needs (a proportional-derivative law on the distance to the
 *    goal and on the goal's speed, with the air cushion's drag fed forward). Its share of that
 *    force (the mobile covers about four blocks) it asks of its neighbours on the side of each
 *    component: the east (west) neighbour blows east (west), the north (south) one north (south)
 *    — a jet drags a mobile over or next to it. A block with no neighbour there blows itself.
 * 3. Two seconds after the path's end the blocks stop: the mobile comes to rest and the run ends.
 *
 * Run it: vsim examples/worlds/smartblocks-conveyor.xml --mobiles-csv traj.csv, then
 * examples/physics/plot-conveyor.sh traj.csv conveyor.png (examples/physics/README.md).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "simcore/blockcode.h"

enum { kNorth = 0, kEast = 1, kSouth = 2, kWest = 3 };
enum { kPathMessage = 1, kFireMessage = 2 };

#define WAYPOINTS 4
#define PERIOD (50 * VS_MS)
static const double kPath[WAYPOINTS][3] = {{0, 75, 425}, {10, 350, 425}, {13, 400, 375}, {24, 400, 75}};

/* The controller's model of the part and of a jet (its own figures, close to the simulator's). */
static const double kMassKg = 0.02, kDragNsPerM = 0.05, kJetN = 0.005;
static const double kCovered = 4.0;         /* blocks under the mobile: each asks for its share */
static const double kKp = 16.0, kKd = 8.0;  /* 1/s^2, 1/s: critically damped at 4 rad/s */

typedef struct path_message {
  uint8_t type;
  int64_t start;                /* ns */
  float points[WAYPOINTS][3];   /* s, mm, mm */
} path_message;

typedef struct fire_message {
  uint8_t type, face;
  float power;
  int64_t duration;
} fire_message;

typedef struct conveyor_state {
  uint8_t knows, covered, ticking;
  int64_t start;
  float points[WAYPOINTS][3];
  double lastT, lastX, lastY; /* the last sample of the mobile, for its speed */
  uint8_t hasLast;
} conveyor_state;

/* The goal and its speed at time t (s) on the path. */
static void goal(const conveyor_state* s, double t, double g[2], double v[2]) {
  v[0] = v[1] = 0;
  if (t <= s->points[0][0]) {
    g[0] = s->points[0][1];
    g[1] = s->points[0][2];
    return;
  }
  for (int i = 0; i + 1 < WAYPOINTS; ++i) {
    const float* a = s->points[i];
    const float* b = s->points[i + 1];
    if (t > b[0]) continue;
    const double d = b[0] - a[0], f = (t - a[0]) / d;
    g[0] = a[1] + f * (b[1] - a[1]);
    g[1] = a[2] + f * (b[2] - a[2]);
    v[0] = (b[1] - a[1]) / d;
    v[1] = (b[2] - a[2]) / d;
    return;
  }
  g[0] = s->points[WAYPOINTS - 1][1];
  g[1] = s->points[WAYPOINTS - 1][2];
}

/* Ask the neighbour on `face` to blow that way (or blow ourselves at the edge). */
static void ask(vs_ctx* c, int face, double power) {
  if (power <= 0) return;
  if (power > 1) power = 1;
  const fire_message m = {kFireMessage, (uint8_t)face, (float)power, PERIOD + 10 * VS_MS};
  if (c->api->neighbor(c, face) == VS_NO_BLOCK || vs_send(c, face, &m, sizeof m, 0) != VS_OK)
    c->api->air_jet(c, face, power, m.duration);
}

static void control(vs_ctx* c) {
  conveyor_state* s = (conveyor_state*)c->state;
  int32_t mobile;
  double p[3];
  if (c->api->mobile_above(c, &mobile, p) != VS_OK) return;
  const double t = (double)(vs_now(c) - s->start) / VS_S;
  double g[2], gv[2];
  goal(s, t, g, gv);
  double v[2] = {gv[0], gv[1]};
  if (s->hasLast && t - s->lastT > 0.01 && t - s->lastT < 0.2) {
    v[0] = (p[0] - s->lastX) / (t - s->lastT);
    v[1] = (p[1] - s->lastY) / (t - s->lastT);
  }
  s->lastT = t, s->lastX = p[0], s->lastY = p[1], s->hasLast = 1;
  for (int axis = 0; axis < 2; ++axis) {
    /* mm and mm/s to SI: the force in N, then this block's share in jet powers. */
    const double a = kKp * (g[axis] - p[axis]) / 1000 + kKd * (gv[axis] - v[axis]) / 1000;
    const double f = (kMassKg * a + kDragNsPerM * gv[axis] / 1000) / kCovered;
    const int face = axis == 0 ? (f > 0 ? kEast : kWest) : (f > 0 ? kNorth : kSouth);
    ask(c, face, fabs(f) / kJetN);
  }
}

static void tick(vs_ctx* c) {
  conveyor_state* s = (conveyor_state*)c->state;
  const double t = (double)(vs_now(c) - s->start) / VS_S;
  if (!s->covered || t > s->points[WAYPOINTS - 1][0] + 2.0) {
    s->ticking = 0;
    s->hasLast = 0;
    return;
  }
  control(c);
  vs_set_timer(c, PERIOD, 0);
}

static void learn(vs_ctx* c, const path_message* m) {
  conveyor_state* s = (conveyor_state*)c->state;
  if (s->knows) return;
  s->knows = 1;
  s->start = m->start;
  memcpy(s->points, m->points, sizeof s->points);
  vs_send_all(c, m, sizeof *m, 0);
  if (s->covered && !s->ticking) {
    s->ticking = 1;
    tick(c);
  }
}

static void on_start(vs_ctx* c) {
  if (c->block != 0) return;
  path_message m;
  memset(&m, 0, sizeof m);
  m.type = kPathMessage;
  m.start = 0;
  for (int i = 0; i < WAYPOINTS; ++i)
    for (int k = 0; k < 3; ++k) m.points[i][k] = (float)kPath[i][k];
  learn(c, &m);
}

static void on_event(vs_ctx* c, const vs_event* ev) {
  conveyor_state* s = (conveyor_state*)c->state;
  switch (ev->kind) {
    case VS_EV_MESSAGE: {
      uint8_t type;
      if (ev->size < 1) return;
      memcpy(&type, ev->data, 1);
      if (type == kPathMessage && ev->size == sizeof(path_message)) {
        path_message m;
        memcpy(&m, ev->data, sizeof m);
        learn(c, &m);
      } else if (type == kFireMessage && ev->size == sizeof(fire_message)) {
        fire_message m;
        memcpy(&m, ev->data, sizeof m);
        c->api->air_jet(c, m.face, m.power, m.duration);
      }
      return;
    }
    case VS_EV_MOBILE:
      s->covered = ev->values[1] != 0;
      if (s->covered && s->knows && !s->ticking) {
        s->ticking = 1;
        tick(c);
      }
      return;
    case VS_EV_TIMER:
      tick(c);
      return;
    default:
      return;
  }
}

static const vs_blockcode conveyor_code = {
    VS_ABI_VERSION, "conveyor", sizeof(conveyor_state), on_start, on_event, NULL, NULL,
};

const vs_blockcode* vs_blockcode_entry(void) { return &conveyor_code; }
