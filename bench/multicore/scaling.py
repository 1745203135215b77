#!/usr/bin/env python3
"""Thread scaling of this toolchain's VM and the established one, from files compiled beforehand.

usage: bench/multicore/scaling.py [options] BASE[=ARGS] ...

BASE is a path without its extension: BASE.mbc (meldc's bytecode) runs on our VM with -j N, and
BASE.m (the established compiler's output, meldc-ref with MELDC_REF_NO_CPP=1) on the established VM
with -c thN when --meld-ref is given and the file exists. Compiling is left to the machine that
has the compilers, so the runs can happen on a machine that has neither (a lent many-core machine
needs only the two VM binaries, which link nothing beyond the C and C++ runtimes). ARGS are passed
to the program (@arg1 ...).

The runs go in rounds: one run of every program, thread count and VM, then the next round, so that
a slow spell of the machine hits every cell alike; a cell is the median of its rounds. A round does
not start when one as long as the last would end past --budget seconds, and the results so far are
written to --json after every round, so a run stopped from outside keeps what it measured. Each
run's peak RSS is its own (GNU time). Our runs pass --stats: the facts derived (a program whose work
depends on the order nodes run in derives more on more threads) and the threads' mean busy and
steal shares come from it.

--check first runs our VM at one and at the most threads and the established VM at th1 with their
dumps on, untimed, and says whether each agrees with the established th1 dump (bench/compare's
comparison: helper predicates left out, numbers within a relative 1e-4).

Options:
  --meld PATH        our VM (default: build/release/apps/meld/meld of this repository)
  --meld-ref PATH    the established VM (its meld binary); without it only ours runs
  --threads LIST     comma-separated thread counts (default 1,2,4,...,nproc)
  --runs N           rounds (default 3)
  --budget S         no round starts that, as long as the last one, would end after S seconds
                     from the start (default: none)
  --timeout S        seconds one run may take (default 300)
  --unscheduled NAME the program NAME runs with --no-scheduling (ours) and -n (established):
                     coordination instructions ignored, as the established suite runs some
  --check            the dump comparison above
  --json FILE        the measurements, rewritten after every round
  --gnu-time PATH    GNU time, for each run's peak RSS (default /usr/bin/time where there is one;
                     without it the RSS columns are empty)
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "compare"))
from compare import agreement, run_group  # noqa: E402  (bench/'s one dump comparison and child runner)


class Failure(Exception):
    pass


def run(cmd, cwd, timeout, gnu_time=None, dump=False):
    """Runs cmd; returns (wall s, peak RSS MB or None, stdout, stderr) or raises Failure.

    The peak RSS comes from GNU time, which forks the program from its own small process: the
    rusage of a child forked by this script would start from this interpreter's own size."""
    rss_file = None
    if gnu_time:
        fd, rss_file = tempfile.mkstemp(prefix="scaling.rss.")
        os.close(fd)
        cmd = [gnu_time, "-f", "%M", "-o", rss_file] + cmd
    start = time.perf_counter()
    try:
        # (A process group of its own: a timeout stops the program too, not only GNU time.)
        p = run_group(cmd, cwd, timeout, stdout=subprocess.PIPE if dump else subprocess.DEVNULL)
        wall = time.perf_counter() - start
        out, err = p.stdout, p.stderr
        rss = None
        if rss_file:
            lines = open(rss_file).read().split()
            rss = int(lines[-1]) / 1024.0 if lines and lines[-1].isdigit() else None
    except subprocess.TimeoutExpired:
        raise Failure("timeout")
    finally:
        if rss_file:
            os.unlink(rss_file)
    if p.returncode != 0:
        last = (err.strip().splitlines() or ["no message"])[-1]
        raise Failure(f"exit {p.returncode}: {last[:80]}")
    return wall, rss, out or "", err


def stat(name, text):
    m = re.search(rf"^{re.escape(name)}: *([0-9.]+)", text, re.M)
    return float(m.group(1)) if m else None


def thread_shares(text):
    """The threads' mean busy and steal percentages from our --stats table."""
    busy, steal = [], []
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("thread") and "busy" in line:
            for row in lines[i + 1:]:
                cells = row.split()
                if len(cells) < 12 or not cells[0].isdigit():
                    break
                busy.append(float(cells[1]))
                steal.append(float(cells[11]))
    if not busy:
        return 100.0, 0.0
    return statistics.mean(busy), statistics.mean(steal)


class Program:
    def __init__(self, spec, unscheduled):
        # The arguments follow the first '=' after which a BASE.mbc exists (generated programs'
        # names hold '=' themselves); without such a file, the first '='.
        base, _, args = spec.partition("=")
        for at in (i for i, c in enumerate(spec) if c == "="):
            if os.path.isfile(spec[:at] + ".mbc"):
                base, args = spec[:at], spec[at + 1:]
                break
        else:
            if os.path.isfile(spec + ".mbc"):
                base, args = spec, ""
        self.base, self.name = os.path.abspath(base), os.path.basename(base)
        self.dir = os.path.dirname(self.base)
        self.args = args.split()
        self.unscheduled = self.name in unscheduled

    def ours(self, meld, threads, dump):
        extra = ["--"] + self.args if self.args else []
        flags = ["--no-scheduling"] if self.unscheduled else []
        return [meld, self.base + ".mbc", "-j", str(threads)] + flags + (
            ["--dump"] if dump else ["--stats"]) + extra

    def established(self, meld_ref, threads, dump):
        extra = ["--"] + self.args if self.args else []
        flags = ["-n"] if self.unscheduled else []
        return [meld_ref, "-f", self.base + ".m", "-c", f"th{threads}"] + flags + (
            ["-d"] if dump else []) + extra


def check(program, a, top):
    """Dumps of ours at 1 and top threads against the established th1 dump."""
    try:
        reference = run(program.established(a.meld_ref, 1, True), program.dir, a.timeout, dump=True)[2]
    except Failure as f:
        return {"reference": str(f)}
    notes = {}
    for t in sorted({1, top}):
        try:
            notes[f"ours -j {t}"] = agreement(run(program.ours(a.meld, t, True), program.dir,
                                                  a.timeout, dump=True)[2], reference)
        except Failure as f:
            notes[f"ours -j {t}"] = str(f)
    return notes


def one_round(programs, a, cells):
    for p in programs:
        for t in a.threads:
            for vm in ("ours", "established"):
                if vm == "established" and not p.has_m:
                    continue
                cell = cells.setdefault(f"{p.name}|{t}|{vm}", {"runs": []})
                if "failed" in cell:
                    continue
                cmd = p.ours(a.meld, t, False) if vm == "ours" else p.established(a.meld_ref, t, False)
                try:
                    wall, rss, _, err = run(cmd, p.dir, a.timeout, a.gnu_time)
                except Failure as f:
                    cell["failed"] = str(f)
                    continue
                sample = {"wall_s": wall, "peak_rss_mb": rss}
                if vm == "ours":
                    sample["facts_derived"] = stat("facts derived", err)
                    sample["busy_pct"], sample["steal_pct"] = thread_shares(err)
                cell["runs"].append(sample)


def median_of(cell, key):
    values = [r[key] for r in cell["runs"] if r.get(key) is not None]
    return statistics.median(values) if values else None


def print_table(programs, a, cells):
    print("| program | threads | ours wall s | ours speedup | ours peak RSS MB | facts derived | busy % "
          "| steal % | established wall s | established speedup | established peak RSS MB | "
          "established / ours |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for p in programs:
        base = {}
        for t in a.threads:
            row = [p.name + (" " + " ".join(p.args) if p.args else ""), str(t)]
            walls = {}
            for vm in ("ours", "established"):
                cell = cells.get(f"{p.name}|{t}|{vm}")
                if cell is None or (not cell["runs"] and "failed" not in cell):
                    row += ["—"] * (6 if vm == "ours" else 3)
                    continue
                if "failed" in cell and not cell["runs"]:
                    row += [cell["failed"][:30]] + ["—"] * (5 if vm == "ours" else 2)
                    continue
                wall = median_of(cell, "wall_s")
                walls[vm] = wall
                base.setdefault(vm, wall)
                rss = median_of(cell, "peak_rss_mb")
                row += [f"{wall:.3f}", f"{base[vm] / wall:.2f}", f"{rss:.1f}" if rss else "—"]
                if vm == "ours":
                    derived = median_of(cell, "facts_derived")
                    row += [f"{derived:,.0f}" if derived else "—",
                            f"{median_of(cell, 'busy_pct'):.1f}", f"{median_of(cell, 'steal_pct'):.1f}"]
            both = walls.get("ours") and walls.get("established")
            row.append(f"{walls['established'] / walls['ours']:.2f}×" if both else "—")
            print("| " + " | ".join(row) + " |")
    print("\nCells: medians over the rounds; speedup: the 1-thread median over this one (the first "
          "thread count given is the base).")


def main():
    p = argparse.ArgumentParser(add_help=False)
    p.add_argument("programs", nargs="*")
    p.add_argument("--meld", default=os.path.join(REPO, "build/release/apps/meld/meld"))
    p.add_argument("--meld-ref")
    p.add_argument("--threads")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--budget", type=float)
    p.add_argument("--timeout", type=float, default=300)
    p.add_argument("--unscheduled", action="append", default=[])
    p.add_argument("--check", action="store_true")
    p.add_argument("--json")
    p.add_argument("--gnu-time", default=shutil.which("time"))
    p.add_argument("-h", "--help", action="store_true")
    a = p.parse_args()
    if a.help:
        print(__doc__.strip())
        return 0
    if not a.programs:
        p.error("no program given (see --help)")
    if a.runs < 1:
        p.error("--runs needs a positive integer")
    if a.threads:
        try:
            a.threads = [int(t) for t in a.threads.split(",")]
        except ValueError:
            p.error(f"--threads needs comma-separated integers, not '{a.threads}'")
        if any(t < 1 for t in a.threads):
            p.error("--threads: thread counts start at 1")
    else:
        a.threads = [1 << k for k in range(0, 16) if 1 << k <= (os.cpu_count() or 1)]
    a.meld = os.path.abspath(a.meld)  # the runs start in their program's folder
    a.meld_ref = a.meld_ref and os.path.abspath(a.meld_ref)
    a.gnu_time = a.gnu_time and os.path.abspath(a.gnu_time)
    for tool in [a.meld] + ([a.meld_ref] if a.meld_ref else []):
        if not os.access(tool, os.X_OK):
            p.error(f"{tool} is not an executable")
    programs = [Program(spec, set(a.unscheduled)) for spec in a.programs]
    for prog in programs:
        if not os.path.isfile(prog.base + ".mbc"):
            p.error(f"{prog.base}.mbc does not exist (compile it with meldc)")
        prog.has_m = bool(a.meld_ref) and os.path.isfile(prog.base + ".m")
    start = time.monotonic()
    result = {"machine": {"cores": os.cpu_count()}, "threads": a.threads, "checks": {}, "cells": {}}
    if a.check:
        for prog in programs:
            if prog.has_m:
                result["checks"][prog.name] = check(prog, a, max(a.threads))
                print(f"scaling: {prog.name}: {result['checks'][prog.name]}", file=sys.stderr, flush=True)
    last_round = 0.0
    for r in range(a.runs):
        # A round is not started when one more as long as the last would end past the budget.
        if a.budget is not None and time.monotonic() - start + last_round > a.budget:
            print(f"scaling: stopped after {r} round(s): another would pass --budget", file=sys.stderr)
            break
        round_start = time.monotonic()
        one_round(programs, a, result["cells"])
        last_round = time.monotonic() - round_start
        result["rounds"] = r + 1
        result["elapsed_s"] = time.monotonic() - start
        print(f"scaling: round {r + 1} done at {result['elapsed_s']:.0f} s", file=sys.stderr, flush=True)
        if a.json:
            with open(a.json, "w") as f:
                json.dump(result, f, indent=1)
    print_table(programs, a, result["cells"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
