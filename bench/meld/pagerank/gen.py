#!/usr/bin/env python3
"""Generate the B2 pagerank program: a random directed graph without dangling nodes.

N nodes @0..@N-1; every node gets exactly D distinct random successors (no self loops), so the
out-degree is D everywhere and the in-degree varies (about Poisson(D)); nodes nobody links to
simply have in-degree 0.

With --power-law the degrees are skewed as in real graphs: out-degrees follow a power law
(exponent 2.1, from 1 up to --max-degree, default 127, rescaled to a mean near D) and successors
are drawn with a Zipf preference (node j with weight 1/(j+1)^0.8), so a few nodes have in-degrees
in the hundreds. --index adds `index contrib/2.` (the iteration of a contribution), so that a
node looks up the contributions of the iteration it collects instead of scanning all that wait.
"""
import bisect
import itertools
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
    p.add_argument("--power-law", action="store_true", help="skewed out- and in-degrees (see above)")
    p.add_argument("--max-degree", type=int, default=127, help="largest out-degree with --power-law")
    p.add_argument("--index", action="store_true", help="add `index contrib/2.` to the program")
    a = p.parse_args()
    if a.nodes < 2 or not 1 <= a.degree < a.nodes or a.iterations < 1 or not 0 < a.damping < 1:
        p.error("need nodes >= 2, 1 <= degree < nodes, iterations >= 1, 0 < damping < 1")
    rng = random.Random(a.seed)
    n = a.nodes
    w = b2gen.Writer(a.output)
    b2gen.header(w, "pagerank", a)
    text = b2gen.program("pagerank", {
        "damping": b2gen.fmt_float(a.damping, 6), "iterations": str(a.iterations)})
    if a.index:  # directives come after the type declarations, before the constants
        text = text.replace("\nconst damping", "\nindex contrib/2.\n\nconst damping", 1)
    w.line(text)
    succ = skewed_successors(rng, n, a) if a.power_law else [
        b2gen.random_successors(rng, n, src, a.degree) for src in range(n)]
    indeg = [0] * n
    for s in succ:
        for dst in s:
            indeg[dst] += 1
    for src in range(n):
        w.line(f"!outdegree(@{src}, {len(succ[src])}). !indegree(@{src}, {indeg[src]}).")
        w.line(" ".join(f"!link(@{src}, @{dst})." for dst in succ[src]))
    w.close()


def skewed_successors(rng, n, a):
    """Power-law out-degrees (mean near a.degree, at most a.max_degree) and Zipf-preferred targets."""
    cap = min(a.max_degree, n - 1)
    raw = [min(cap, int(rng.paretovariate(1.1))) for _ in range(n)]
    scale = a.degree / (sum(raw) / n)
    degrees = [max(1, min(cap, round(d * scale))) for d in raw]
    weights = [1.0 / (j + 1) ** 0.8 for j in range(n)]
    cumulative = list(itertools.accumulate(weights))
    succ = []
    for src in range(n):
        chosen = set()
        while len(chosen) < degrees[src]:
            dst = bisect.bisect_left(cumulative, rng.random() * cumulative[-1])
            if dst != src and dst < n:
                chosen.add(dst)
        succ.append(sorted(chosen))
    return succ


if __name__ == "__main__":
    main()
