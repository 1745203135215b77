#!/usr/bin/env bash
# Compile time of axiom-heavy programs: meldc on the B2 generators' programs (a shortest-path graph
# of N nodes with 8 arcs each, a W x W heat-transfer grid), wall seconds and peak RSS of
# `meldc FILE.meld -o FILE.mbc`, median of --runs runs, and per axiom (µs, bytes).
#   bench/meldc/run-axioms.sh                     # 20,000 nodes (160,020 axioms), 100 x 100 grid
#   bench/meldc/run-axioms.sh --nodes 100000 --width 300 --runs 5
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."

MELDC=${MELDC:-build/release/meldc/meldc}
NODES=20000
WIDTH=100
RUNS=3
while [ $# -gt 0 ]; do
  case "$1" in
    --nodes) NODES=$2; shift 2 ;;
    --width) WIDTH=$2; shift 2 ;;
    --runs) RUNS=$2; shift 2 ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "run-axioms.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$MELDC" ] || { echo "run-axioms.sh: no compiler at $MELDC (build the release preset, or set MELDC)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "run-axioms.sh: needs /usr/bin/time (Debian package 'time')" >&2; exit 1; }

OUT=build/bench/meldc
mkdir -p "$OUT"
python3 bench/meld/shortest-path/gen.py --nodes "$NODES" -o "$OUT/shortest-path.meld"
python3 bench/meld/heat-transfer/gen.py --width "$WIDTH" -o "$OUT/heat-transfer.meld"

printf '%-15s %10s %8s %9s %8s %10s\n' program axioms "wall s" "peak MB" "µs/axiom" "bytes/axiom"
for prog in shortest-path heat-transfer; do
  src="$OUT/$prog.meld"
  axioms=$(grep -oE '(^|[. ])!?[a-z][-a-z]*\(@[0-9]+[^)]*\)\.' "$src" | wc -l)
  results=()
  for _ in $(seq "$RUNS"); do
    /usr/bin/time -f '%e %M' -o "$OUT/$prog.time" "$MELDC" "$src" -o "$OUT/$prog.mbc"
    results+=("$(cat "$OUT/$prog.time")")
  done
  median=$(printf '%s\n' "${results[@]}" | sort -n | sed -n "$(( (RUNS + 1) / 2 ))p")
  read -r wall kb <<<"$median"
  awk -v p="$prog" -v a="$axioms" -v w="$wall" -v kb="$kb" 'BEGIN {
    printf "%-15s %10d %8.2f %9.1f %8.2f %10.0f\n", p, a, w, kb / 1024, w * 1e6 / a, kb * 1024 / a }'
done
