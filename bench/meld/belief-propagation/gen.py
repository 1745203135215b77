#!/usr/bin/env python3
"""Generate the B2 belief-propagation program: a noisy label image on a W x W grid.

Cell (x, y) is node @(y*W + x), with its left, right, upper and lower neighbours. The hidden
image has K labels in Voronoi regions around 3K random centres; each cell observes its label,
replaced by a random label with probability --noise. Node potentials (log space):
log(0.8) for the observed label, log(0.2/(K-1)) for the others, plus a jitter in [-0.05, 0.05].
Coupling (log space): -beta * min(|i - j|, 2) between labels i and j (truncated linear).
"""
import math
import os
import random
import sys

sys.dont_write_bytecode = True  # keep the source tree clean (no __pycache__)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import b2gen  # noqa: E402


def main():
    p = b2gen.parser(__doc__.splitlines()[0])
    p.add_argument("--width", type=int, default=128, help="grid side W (default 128)")
    p.add_argument("--labels", type=int, default=5, help="number of labels K (default 5)")
    p.add_argument("--iterations", type=int, default=50, help="BP rounds (default 50)")
    p.add_argument("--damping", type=float, default=0.5,
                   help="weight of the new message when damping (default 0.5)")
    p.add_argument("--beta", type=float, default=1.0, help="coupling strength (default 1.0)")
    p.add_argument("--noise", type=float, default=0.3,
                   help="probability that a cell observes a random label (default 0.3)")
    a = p.parse_args()
    if a.width < 2 or a.labels < 2 or a.iterations < 1 or not 0 < a.damping <= 1 or a.beta < 0 \
            or not 0 <= a.noise <= 1:
        p.error("need width >= 2, labels >= 2, iterations >= 1, 0 < damping <= 1, beta >= 0, "
                "0 <= noise <= 1")
    rng = random.Random(a.seed)
    W, K = a.width, a.labels
    coupling = [-a.beta * min(abs(i - j), 2) for i in range(K) for j in range(K)]
    uniform = [-math.log(K)] * K
    w = b2gen.Writer(a.output)
    b2gen.header(w, "belief-propagation", a)
    w.line(b2gen.program("belief-propagation", {
        "iterations": str(a.iterations),
        "damping": b2gen.fmt_float(a.damping, 6),
        "coupling": b2gen.float_list(coupling),
        "uniform": b2gen.float_list(uniform, 6)}))
    centres = [(rng.uniform(0, W), rng.uniform(0, W), rng.randrange(K)) for _ in range(3 * K)]
    hit, miss = math.log(0.8), math.log(0.2 / (K - 1))
    for i in range(W * W):
        x, y = i % W, i // W
        label = min(centres, key=lambda c: (c[0] - x) ** 2 + (c[1] - y) ** 2)[2]
        if rng.random() < a.noise:
            label = rng.randrange(K)
        pot = [(hit if k == label else miss) + rng.uniform(-0.05, 0.05) for k in range(K)]
        nb = []
        if x > 0:
            nb.append(i - 1)
        if x < W - 1:
            nb.append(i + 1)
        if y > 0:
            nb.append(i - W)
        if y < W - 1:
            nb.append(i + W)
        w.line(f"!degree(@{i}, {len(nb)}). !potential(@{i}, {b2gen.float_list(pot)}).")
        w.line(" ".join(f"!edge(@{i}, @{j})." for j in nb))
    w.close()


if __name__ == "__main__":
    main()
