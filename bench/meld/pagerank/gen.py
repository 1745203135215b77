#!/usr/bin/env python3
"""Generate the B2 pagerank program: a random directed graph without dangling nodes.

N nodes @0..@N-1; every node gets exactly D distinct random successors (no self loops), so the
out-degree is D everywhere and the in-degree varies (about Poisson(D)); nodes nobody links to
simply have in-degree 0.
"""
import os
import random
import sys

sys.dont_write_bytecode = True  # keep the source tree clean (no __pycache__)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import b2gen  # noqa: E402


def main():
    p = b2gen.parser(__doc__.splitlines()[0])
    p.add_argument("--nodes", type=int, default=20000, help="number of nodes N (default 20000)")
    p.add_argument("--degree", type=int, default=8, help="out-degree D of every node (default 8)")
    p.add_argument("--iterations", type=int, default=100, help="PageRank iterations (default 100)")
    p.add_argument("--damping", type=float, default=0.85, help="damping factor (default 0.85)")
    a = p.parse_args()
    if a.nodes < 2 or not 1 <= a.degree < a.nodes or a.iterations < 1 or not 0 < a.damping < 1:
        p.error("need nodes >= 2, 1 <= degree < nodes, iterations >= 1, 0 < damping < 1")
    rng = random.Random(a.seed)
    n = a.nodes
    w = b2gen.Writer(a.output)
    b2gen.header(w, "pagerank", a)
    w.line(b2gen.program("pagerank", {
        "damping": b2gen.fmt_float(a.damping, 6), "iterations": str(a.iterations)}))
    succ = []
    indeg = [0] * n
    for src in range(n):
        s = b2gen.random_successors(rng, n, src, a.degree)
        for dst in s:
            indeg[dst] += 1
        succ.append(s)
    for src in range(n):
        w.line(f"!outdegree(@{src}, {len(succ[src])}). !indegree(@{src}, {indeg[src]}).")
        w.line(" ".join(f"!link(@{src}, @{dst})." for dst in succ[src]))
    w.close()


if __name__ == "__main__":
    main()
