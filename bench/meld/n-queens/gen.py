#!/usr/bin/env python3
"""Generate the B2 n-queens program: an N x N board of cells, one node per cell.

Cell (column c, row r) is node @(c*N + r). The search has no randomness; --seed is accepted for
uniformity with the other generators and ignored.
"""
import os
import sys

sys.dont_write_bytecode = True  # keep the source tree clean (no __pycache__)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import b2gen  # noqa: E402


def main():
    p = b2gen.parser(__doc__.splitlines()[0])
    p.add_argument("--queens", "-n", type=int, default=13, help="board side N (default 13)")
    a = p.parse_args()
    if not 4 <= a.queens <= 16:
        p.error("need 4 <= queens <= 16")
    n = a.queens
    w = b2gen.Writer(a.output)
    b2gen.header(w, "n-queens", a)
    w.line(b2gen.program("n-queens", {}))
    for r in range(n):
        w.line(f"partial(@{r}, [{r}]).")
    for c in range(n - 1):
        for r in range(n):
            src = c * n + r
            w.line(" ".join(f"!next(@{src}, @{(c + 1) * n + y}, {y})." for y in range(n)))
    for r in range(n):
        last = (n - 1) * n + r
        w.line(f"!last(@{last}). solutions(@{last}, 0).")
    w.close()


if __name__ == "__main__":
    main()
