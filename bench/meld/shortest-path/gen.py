#!/usr/bin/env python3
"""Generate the B2 shortest-path program: a random weighted directed graph.

N nodes @0..@N-1; every node gets exactly D distinct random successors (no self loops), each arc
with a weight uniform in 1..MAXW; the source is node S (default 0).
"""
import os
import random
import sys

sys.dont_write_bytecode = True  # keep the source tree clean (no __pycache__)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import b2gen  # noqa: E402


def main():
    p = b2gen.parser(__doc__.splitlines()[0])
    p.add_argument("--nodes", type=int, default=100000, help="number of nodes N (default 100000)")
    p.add_argument("--degree", type=int, default=8, help="out-degree D of every node (default 8)")
    p.add_argument("--max-weight", type=int, default=100, help="weights are 1..MAXW (default 100)")
    p.add_argument("--source", type=int, default=0, help="source node S (default 0)")
    a = p.parse_args()
    if a.nodes < 2 or not 1 <= a.degree < a.nodes or a.max_weight < 1 or not 0 <= a.source < a.nodes:
        p.error("need nodes >= 2, 1 <= degree < nodes, max-weight >= 1, 0 <= source < nodes")
    rng = random.Random(a.seed)
    w = b2gen.Writer(a.output)
    b2gen.header(w, "shortest-path", a)
    w.line(b2gen.program("shortest-path", {}))
    w.line(f"!path(@{a.source}, 0).")
    n = a.nodes
    for src in range(n):
        for dst in b2gen.random_successors(rng, n, src, a.degree):
            w.line(f"!edge(@{src}, @{dst}, {rng.randint(1, a.max_weight)}).")
    w.close()


if __name__ == "__main__":
    main()
