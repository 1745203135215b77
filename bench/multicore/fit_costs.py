#!/usr/bin/env python3
"""Fits the multicore target's core costs (vsim --costs) to measured `meld --stats` runs.

usage: fit_costs.py LOGDIR   (calibrate.sh writes LOGDIR/PROGRAM.j1.log and PROGRAM.j2.log, the
                              median runs of `meld -j 1 --stats` and `meld -j 2 --stats`)

1. Serial: wall = node x node runs + rule x rules fired + fact x facts derived + tried x facts
   tried (looked at by the rules' loops, matching or not), least squares on the relative error
   over the programs (their costs per step still differ: lists of floats cost more than
   integers, so each program also gets its own scale, its serial wall over the model's).
2. Two cores at once: each -j 2 thread's busy time, divided by its program's scale, is
   (1 + contention) x the serial model of its own node runs (both cores busy slow each other
   down: shared caches and memory) + crossing x its facts out and in + byte x their bytes (a
   fact that carries a list costs more to encode and rebuild): one cost per fact and one per
   byte, the same at the sending and the receiving end (out and in are nearly equal on two
   threads, so the two ends cannot be told apart).
3. Rebalancing: each thread's time in rebalances after both threads arrived ("move ms": moving
   nodes, not waiting for the other thread to end its node run, which the chip simulates by
   itself) = rounds x rebalance + nodes moved x move + movebyte x (every byte moved, which all
   threads wait for while the givers encode it, + the bytes this thread took, which it alone
   rebuilds while the others go on: vm/threads' worker.cpp, phase 4). Bytes of
   moving nodes get their own cost: a node that carries thousands of placements with their lists
   (n-queens) costs per byte what scalar facts crossing threads (pagerank) cannot tell.
Prints the --costs string and the fit, per program.
"""
import os
import re
import sys


def parse(path):
    totals, threads = {}, []
    with open(path) as f:
        for line in f:
            m = re.match(r"^([a-zA-Z /%]+): ([0-9.]+)$", line.strip())
            if m:
                totals[m.group(1)] = float(m.group(2))
                continue
            cols = line.split()
            if len(cols) >= 17 and cols[0].isdigit():
                threads.append([float(c) for c in cols])
    return totals, threads


def lstsq(rows, targets):
    """Least squares by the normal equations (a handful of unknowns); unknowns that come out
    negative are fixed at 0 and the rest fitted again."""
    n = len(rows[0])
    active = list(range(n))
    while True:
        a = [[sum(r[i] * r[j] for r in rows) for j in active] for i in active]
        b = [sum(r[i] * t for r, t in zip(rows, targets)) for i in active]
        m = len(active)
        for c in range(m):  # Gauss-Jordan with partial pivoting
            p = max(range(c, m), key=lambda k: abs(a[k][c]))
            a[c], a[p], b[c], b[p] = a[p], a[c], b[p], b[c]
            if abs(a[c][c]) < 1e-300:
                continue
            for k in range(m):
                if k != c:
                    f = a[k][c] / a[c][c]
                    a[k] = [x - f * y for x, y in zip(a[k], a[c])]
                    b[k] -= f * b[c]
        x = [b[c] / a[c][c] if abs(a[c][c]) > 1e-300 else 0.0 for c in range(m)]
        if all(v >= 0 for v in x) or len(active) == 1:
            out = [0.0] * n
            for i, v in zip(active, x):
                out[i] = max(v, 0.0)
            return out
        active = [i for i, v in zip(active, x) if v > 0]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    logdir = sys.argv[1]
    programs = sorted({f.split(".j")[0] for f in os.listdir(logdir) if f.endswith(".j1.log")})
    if not programs:
        sys.exit("fit_costs.py: no PROGRAM.j1.log in " + logdir)
    serial = {p: parse(os.path.join(logdir, p + ".j1.log"))[0] for p in programs}
    counts = lambda s: [s["node runs"], s["rules fired"], s["facts derived"], s["facts tried"]]
    rows = [[c / s["wall s"] for c in counts(s)] for s in serial.values()]
    node, rule, fact, tried = lstsq(rows, [1.0] * len(rows))
    model = lambda runs, rules, facts, looked: node * runs + rule * rules + fact * facts + tried * looked
    scale = {p: s["wall s"] / model(*counts(s)) for p, s in serial.items()}

    cross_rows, cross_targets, steal_rows, steal_targets = [], [], [], []
    for p in programs:
        path = os.path.join(logdir, p + ".j2.log")
        if not os.path.exists(path):
            continue
        totals, threads = parse(path)
        wall = totals["wall s"]
        all_bytes = sum(t[13] for t in threads)
        all_moved = sum(t[15] for t in threads)
        for t in threads:
            busy_pct, runs, rules, facts, out, inn = t[1], t[2], t[3], t[4], t[5], t[6]
            taken, given, rounds, bytes_out, looked = t[9], t[10], t[12], t[13], t[14]
            bytes_in = all_bytes - bytes_out  # two threads: what the other one sent
            cross_rows.append([model(runs, rules, facts, looked), out + inn, bytes_out + bytes_in])
            cross_targets.append(wall * busy_pct / 100 / scale[p])
            moved_bytes, move_ms = t[15], t[16]
            took_bytes = all_moved - moved_bytes  # two threads: what the other one gave
            steal_rows.append([rounds, taken + given, all_moved + took_bytes])
            steal_targets.append(move_ms / 1e3)
    slowdown, crossing, byte = lstsq(cross_rows, cross_targets) if cross_rows else (1.0, 0.0, 0.0)
    contention = max(slowdown - 1, 0.0)
    rebalance, move, movebyte = lstsq(steal_rows, steal_targets) if steal_rows else (0.0, 0.0, 0.0)
    ns = lambda v: v * 1e9 + 0.0  # + 0.0: no "-0.00"
    print("fit (ns): node %.1f, rule %.1f, fact %.1f, fact tried %.2f; a fact crossing cores %.1f at each end,"
          " a byte %.2f at each end; rebalance %.0f, node moved %.0f, a byte moved %.2f at each end;"
          " contention %.2f" % (ns(node), ns(rule), ns(fact), ns(tried), ns(crossing), ns(byte), ns(rebalance),
                                ns(move), ns(movebyte), contention))
    print("serial fit per program (measured s, model s, scale):")
    for p, s in serial.items():
        m = model(*counts(s))
        print("  %-60s %8.3f %8.3f %6.2f" % (p, s["wall s"], m, scale[p]))
    print("--costs node=%.0f,rule=%.0f,fact=%.0f,tried=%.2f,send=%.0f,receive=%.0f,byte=%.2f,rebalance=%.0f,move=%.0f,"
          "movebyte=%.2f,contention=%.2f" % (ns(node), ns(rule), ns(fact), ns(tried), ns(crossing), ns(crossing),
                                             ns(byte), ns(rebalance), ns(move), ns(movebyte), contention))


main()
