#!/usr/bin/env python3
"""Generate the B2 heat-transfer program: a W x W grid with random initial temperatures.

Cell (x, y) is node @(y*W + x); its neighbours are the cells left, right, above and below it.
Initial temperatures are uniform in [0, 100) with two decimals.
"""
import os
import random
import sys

sys.dont_write_bytecode = True  # keep the source tree clean (no __pycache__)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import b2gen  # noqa: E402


def main():
    p = b2gen.parser(__doc__.splitlines()[0])
    p.add_argument("--width", type=int, default=100, help="grid side W (default 100)")
    p.add_argument("--epsilon", type=float, default=0.001,
                   help="change below which neighbours are not woken up (default 0.001)")
    p.add_argument("--max-rounds", type=int, default=1000,
                   help="most updates one cell performs (default 1000)")
    a = p.parse_args()
    if a.width < 2 or a.epsilon <= 0 or a.max_rounds < 1:
        p.error("need width >= 2, epsilon > 0, max-rounds >= 1")
    rng = random.Random(a.seed)
    W = a.width
    w = b2gen.Writer(a.output)
    b2gen.header(w, "heat-transfer", a)
    w.line(b2gen.program("heat-transfer", {
        "epsilon": b2gen.fmt_float(a.epsilon, 6), "maxrounds": str(a.max_rounds)}))
    temp = [f"{rng.randrange(10000) / 100:.2f}" for _ in range(W * W)]

    def neighbours(i):
        x, y = i % W, i // W
        out = []
        if x > 0:
            out.append(i - 1)
        if x < W - 1:
            out.append(i + 1)
        if y > 0:
            out.append(i - W)
        if y < W - 1:
            out.append(i + W)
        return out

    for i in range(W * W):
        nb = neighbours(i)
        w.line(f"!degree(@{i}, {len(nb)}). heat(@{i}, {temp[i]}, 0).")
        for j in nb:
            w.line(f"!edge(@{i}, @{j}). neighbor-heat(@{i}, @{j}, {temp[j]}).")
    w.close()


if __name__ == "__main__":
    main()
