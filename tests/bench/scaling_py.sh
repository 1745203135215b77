#!/bin/sh
# bench/multicore/scaling.py as a program (not timed): on a tiny program whose file name holds '='
# and which takes an argument, every cell of two rounds at 1 and 2 threads is measured, the same
# facts are derived on both, the JSON is written, and bad input is refused with exit status 2.
set -u
MELD=$1 MELDC=$2 SCRIPT=$3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cat > "$WORK/ring_n=3.meld" <<'MELD'
type route edge(node, node).
type linear token(node, int).
type linear passes(node, int).
const limit = str2int(@arg1).
!edge(@0, @1). !edge(@1, @2). !edge(@2, @0).
token(@0, 0).
passes(A, 0).
token(A, N), N < limit, !edge(A, B), passes(A, K) -o token(B, N + 1), passes(A, K + 1).
MELD
"$MELDC" "$WORK/ring_n=3.meld" -o "$WORK/ring_n=3.mbc" || fail "meldc"
python3 "$SCRIPT" --meld "$MELD" --threads 1,2 --runs 2 --json "$WORK/out.json" "$WORK/ring_n=3=30" \
  > "$WORK/table.md" 2> "$WORK/err.txt" || fail "scaling.py failed: $(cat "$WORK/err.txt")"
grep -q '^| ring_n=3 30 | 1 | ' "$WORK/table.md" || fail "no row for 1 thread: $(cat "$WORK/table.md")"
grep -q '^| ring_n=3 30 | 2 | ' "$WORK/table.md" || fail "no row for 2 threads"
python3 - "$WORK/out.json" <<'PY' || fail "the JSON does not hold what was measured"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["rounds"] == 2 and r["threads"] == [1, 2], r
cells = r["cells"]
for t in (1, 2):
    runs = cells[f"ring_n=3|{t}|ours"]["runs"]
    assert len(runs) == 2, runs
    # 30 tokens passed and 30 counts updated, plus the 3 + 1 starting facts: the same on both
    assert all(s["facts_derived"] == runs[0]["facts_derived"] > 60 for s in runs), runs
assert cells["ring_n=3|1|ours"]["runs"][0]["facts_derived"] == cells["ring_n=3|2|ours"]["runs"][0]["facts_derived"]
PY
python3 "$SCRIPT" --meld "$MELD" "$WORK/missing" > /dev/null 2>&1
[ $? -eq 2 ] || fail "a missing program is not refused with status 2"
python3 "$SCRIPT" --meld "$MELD" --threads 1,x "$WORK/ring_n=3" > /dev/null 2>&1
[ $? -eq 2 ] || fail "a bad thread list is not refused with status 2"
echo "scaling.py: ok"
