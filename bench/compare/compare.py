#!/usr/bin/env python3
"""Runs Meld programs on this toolchain and on the established one, side by side.

usage: bench/compare/compare.py --anchors DIR [options] PROGRAM.meld[=ARGS] ...

Each program is compiled once per toolchain: ours to bytecode (meldc) and to a shared object
(meldc --emit=native); the established one's .m file (meldc-ref, with its C++ back end off). Then
every mode runs RUNS times, the modes interleaved (one run of each mode, then the next round), so
that a slow spell of the machine hits every column alike; each cell is the median wall time.
Before the timed runs, each mode runs once with its dump on and the dumps are compared with the
established single-threaded VM's: "same" when they agree line by line (helper predicates ___* and
__mangledname* left out, numbers within a relative 1e-4, as the conformance script compares them),
otherwise the first line that differs. A figure is only worth comparing where the dumps agree (or
the program's result depends on the order nodes run in, which the note column cannot tell).

PROGRAM.meld=ARGS passes ARGS (blank-separated) to the program (@arg1 ...). A program of the
established suite (its benchs/progs or tests/progs) with a file ../args/NAME gets that file's
PROG_ARGS when no ARGS are given, and its MELD_ARGS' -n (coordination instructions ignored): -n for
the established VM, --no-scheduling for ours. Programs run from their own folder, so their includes
and data files are found as the established VM finds them.

Modes (--modes, separated by commas or spaces; default bc,so,j2,ref1,ref2):
  bc    meld X.mbc               (ours, bytecode)
  so    meld X.so                (ours, native code)
  jit   meld X.mbc --jit         (ours, native code compiled in memory: compile time included)
  j2    meld X.mbc -j 2          (ours, two threads)
  ref1  meld-ref -f X.m -c th1   (established VM, one thread)
  ref2  meld-ref -f X.m -c th2   (established VM, two threads)

Options:
  --anchors DIR  where shared/tools/build-anchors.sh put meld-ref and meldc-ref (or $MELD_ANCHORS)
  --runs N       timed runs per mode (default 3)
  --modes LIST   the columns, as above
  --timeout S    seconds a run may take (default 600); a run past it is shown as "timeout"
  --compile-timeout S
                 seconds a compiler may take on one program (default: --timeout); the modes of a
                 compile past it are shown as "compile: timed out" and the others still run (the
                 established compiler takes over half an hour on B2 shortest-path here)
  --json         one JSON record per program instead of the table
  --workdir DIR  compiled files (default: a temporary folder, removed at the end)
MELD and MELDC name our binaries (default: build/release/apps/meld/meld and build/release/meldc/meldc
of this repository).
"""
import argparse
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MODES = ["bc", "so", "jit", "j2", "ref1", "ref2"]
TITLES = {"bc": "ours bytecode", "so": "ours .so", "jit": "ours --jit", "j2": "ours -j 2",
          "ref1": "established th1", "ref2": "established th2"}


class Failure(Exception):
    pass


def run_group(cmd, cwd, timeout, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=None):
    """subprocess.run in a process group of its own: on a timeout the whole group is killed (the
    established compiler is a script whose compiler process outlived a plain kill, and took a
    core from every run after it), then TimeoutExpired is raised. scaling.py runs its VMs with it."""
    p = subprocess.Popen(cmd, cwd=cwd, stdout=stdout, stderr=stderr, env=env, text=True,
                         errors="replace", start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        raise
    return subprocess.CompletedProcess(cmd, p.returncode, out, err)


def run(cmd, cwd, timeout):
    """Runs cmd; returns (wall seconds, stdout) or raises Failure with the reason."""
    start = time.perf_counter()
    try:
        p = run_group(cmd, cwd, timeout)
    except subprocess.TimeoutExpired:
        raise Failure("timeout")
    wall = time.perf_counter() - start
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["no message"])[-1]
        raise Failure(f"exit {p.returncode}: {last[:80]}")
    return wall, p.stdout


class Program:
    def __init__(self, spec, tools, workdir):
        # The arguments follow the first ".meld=" (generated names may hold '=' themselves).
        m = re.match(r"(.*?\.meld)(?:=(.*))?$", spec)
        path, args = (m.group(1), m.group(2) or "") if m else (spec, "")
        if not os.path.isfile(path):
            raise SystemExit(f"compare: no such program: {path}")
        self.path = os.path.abspath(path)
        self.name = os.path.splitext(os.path.basename(path))[0]
        self.dir = os.path.dirname(self.path)
        self.args = args.split()
        # A program of the established suite (benchs/progs, tests/progs) may have ../args/NAME:
        # PROG_ARGS (used unless ARGS were given) and MELD_ARGS, whose -n (no coordination) both
        # VMs then get (ours: --no-scheduling).
        self.ref_flags, self.our_flags = [], []
        suite_args = os.path.join(self.dir, "..", "args", self.name)
        if os.path.isfile(suite_args):
            values = dict(re.findall(r'^(\w+)="?([^"\n]*)"?', open(suite_args).read(), re.M))
            if not self.args:
                self.args = values.get("PROG_ARGS", "").split()
            if "-n" in values.get("MELD_ARGS", "").split():
                self.ref_flags, self.our_flags = ["-n"], ["--no-scheduling"]
        self.tools = tools
        base = os.path.join(workdir, self.name)
        os.makedirs(base, exist_ok=True)
        self.mbc, self.so, self.m = (os.path.join(base, self.name + ext) for ext in (".mbc", ".so", ".m"))

    def prepare(self, modes, timeout):
        """Compiles what the modes need; returns {mode: reason} for the modes that cannot run."""
        broken = {}
        steps = []
        if {"bc", "jit", "j2"} & set(modes):
            steps.append((("bc", "jit", "j2"), [self.tools.meldc, self.path, "-o", self.mbc]))
        if "so" in modes:
            steps.append((("so",), [self.tools.meldc, "--emit=native", "--no-progress", self.path, "-o", self.so]))
        if {"ref1", "ref2"} & set(modes):
            steps.append((("ref1", "ref2"), [self.tools.meldc_ref, self.path, self.m]))
        env = dict(os.environ, MELDC_REF_NO_CPP="1")
        for affected, cmd in steps:
            try:
                p = run_group(cmd, self.dir, timeout, stderr=subprocess.STDOUT, env=env)
                why = None if p.returncode == 0 else \
                    "compile: " + ((p.stdout.strip().splitlines() or ["failed"])[-1])[:70]
            except subprocess.TimeoutExpired:
                why = f"compile: timed out after {timeout:g} s"
            if why:
                for mode in affected:
                    broken[mode] = why
        return broken

    def command(self, mode, dump):
        t = self.tools
        extra = (["--"] + self.args) if self.args else []
        if mode in ("bc", "so", "jit", "j2"):
            target = self.so if mode == "so" else self.mbc
            flags = {"jit": ["--jit"], "j2": ["-j", "2"]}.get(mode, [])
            return [t.meld, target] + flags + self.our_flags + (["--dump"] if dump else []) + extra
        sched = "th1" if mode == "ref1" else "th2"
        return [t.meld_ref, "-f", self.m, "-c", sched] + self.ref_flags + (["-d"] if dump else []) + extra


NUMBER = re.compile(r"-?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def normalised(dump):
    """The dump's lines without the compiler's helper predicates."""
    out = []
    for line in dump.splitlines():
        name = line.lstrip("!")
        if name.startswith("___") or name.startswith("__mangledname"):
            continue
        out.append(line.rstrip())
    return out


def same_line(a, b):
    if a == b:
        return True
    # Numbers with a point or an exponent within a relative 1e-4 (dumps print %.5g); integers,
    # node and thread references exactly.
    split_a, split_b = NUMBER.split(a), NUMBER.split(b)
    if split_a != split_b:
        return False
    for x, y in zip(NUMBER.findall(a), NUMBER.findall(b)):
        if not any(c in x + y for c in ".eE"):  # integers (and node ids) exactly
            if int(x) != int(y):
                return False
            continue
        fx, fy = float(x), float(y)
        if fx != fy and abs(fx - fy) > 1e-4 * max(abs(fx), abs(fy)):
            return False
    return True


def agreement(dump, reference):
    mine, ref = normalised(dump), normalised(reference)
    for i, (a, b) in enumerate(zip(mine, ref)):
        if not same_line(a, b):
            return f"line {i + 1}: {a[:40]!r} vs {b[:40]!r}"
    if len(mine) != len(ref):
        return f"{len(mine)} lines vs {len(ref)}"
    return "same"


def compare(program, modes, runs, timeout, compile_timeout):
    broken = program.prepare(modes, compile_timeout)
    dumps, notes = {}, {}
    for mode in modes:
        if mode in broken:
            continue
        try:
            dumps[mode] = run(program.command(mode, True), program.dir, timeout)[1]
        except Failure as f:
            broken[mode] = str(f)
    times = {mode: [] for mode in modes if mode not in broken}
    for _ in range(runs):
        for mode in list(times):
            try:
                times[mode].append(run(program.command(mode, False), program.dir, timeout)[0])
            except Failure as f:
                broken[mode] = str(f)
                del times[mode]
    reference = dumps.get("ref1")
    for mode in modes:
        if mode in dumps and mode != "ref1" and reference is not None:
            notes[mode] = agreement(dumps[mode], reference)
    medians = {mode: statistics.median(t) for mode, t in times.items() if t}
    return {"program": program.name, "args": program.args, "runs": runs,
            "median_s": medians, "failed": broken, "dump_vs_ref1": notes}


def print_table(records, modes):
    head = ["program"] + [TITLES[m] for m in modes]
    ours = [m for m in modes if not m.startswith("ref")]
    if "ref1" in modes:
        head += [f"ref1 / {m}" for m in ours] + ["dumps vs ref1"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in records:
        med = r["median_s"]
        cells = [r["program"] + (" " + " ".join(r["args"]) if r["args"] else "")]
        cells += [f"{med[m]:.3f}" if m in med else r["failed"].get(m, "-")[:40] for m in modes]
        if "ref1" in modes:
            for m in ours:
                cells.append(f"{med['ref1'] / med[m]:.2f}x" if m in med and "ref1" in med and med[m] > 0 else "-")
            notes = r["dump_vs_ref1"]
            differing = [f"{m}: {notes[m]}" for m in ours if notes.get(m, "same") != "same"]
            cells.append("; ".join(differing) if differing else ("same" if notes else "-"))
        print("| " + " | ".join(cells) + " |")
    print("\nCells: median wall s. ref1 / mode > 1: ours is that many times faster than the established "
          "VM on one thread.")


class Tools:
    def __init__(self, anchors):
        # Absolute: the programs run from their own folders.
        self.meld = os.path.abspath(os.environ.get("MELD", os.path.join(REPO, "build/release/apps/meld/meld")))
        self.meldc = os.path.abspath(os.environ.get("MELDC", os.path.join(REPO, "build/release/meldc/meldc")))
        self.meld_ref = os.path.abspath(os.path.join(anchors, "meld-ref"))
        self.meldc_ref = os.path.abspath(os.path.join(anchors, "meldc-ref"))

    def check(self, modes):
        needed = [self.meld, self.meldc] if any(not m.startswith("ref") for m in modes) else []
        needed += [self.meld_ref, self.meldc_ref] if any(m.startswith("ref") for m in modes) else []
        for tool in needed:
            if not os.access(tool, os.X_OK):
                raise SystemExit(f"compare: {tool} is not an executable (build it, or see --help)")


def main():
    p = argparse.ArgumentParser(add_help=False)
    p.add_argument("programs", nargs="*")
    p.add_argument("--anchors", default=os.environ.get("MELD_ANCHORS"))
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--modes", default="bc,so,j2,ref1,ref2")
    p.add_argument("--timeout", type=float, default=600)
    p.add_argument("--compile-timeout", type=float)
    p.add_argument("--json", action="store_true")
    p.add_argument("--workdir")
    p.add_argument("-h", "--help", action="store_true")
    a = p.parse_args()
    if a.help:
        print(__doc__.strip())
        return 0
    modes = [m for m in re.split(r"[,\s]+", a.modes) if m]  # "bc,so" or "bc so", as suite.sh takes them
    unknown = [m for m in modes if m not in MODES]
    if unknown or not modes:
        p.error(f"unknown mode(s) {', '.join(unknown) or '(none)'}: choose among {', '.join(MODES)}")
    if a.runs < 1:
        p.error("--runs needs a positive integer")
    if not a.programs:
        p.error("no program given (see --help)")
    if any(m.startswith("ref") for m in modes) and not a.anchors:
        p.error("--anchors DIR is needed for the established toolchain's modes (or set MELD_ANCHORS)")
    tools = Tools(a.anchors or "")
    tools.check(modes)
    workdir = a.workdir or tempfile.mkdtemp(prefix="meld-compare.")
    try:
        records = []
        for spec in a.programs:
            record = compare(Program(spec, tools, workdir), modes, a.runs, a.timeout,
                             a.compile_timeout or a.timeout)
            records.append(record)
            if a.json:
                print(json.dumps(record), flush=True)
            else:
                print(f"compare: {record['program']} done", file=sys.stderr, flush=True)
        if not a.json:
            print_table(records, modes)
    finally:
        if not a.workdir:
            shutil.rmtree(workdir, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
