#!/usr/bin/env bash
# The side-by-side table of bench/meld/README.md: the established toolchain's own five programs
# and the five B2 programs of this project, on both toolchains (compare.py, interleaved runs,
# medians), with the dump check.
#   bench/compare/table.sh [--anchors DIR] [--suite DIR] [--runs K] [--modes LIST] [--json]
#                          [--only "name ..."] [--compile-timeout S]
# --anchors: where ../shared/tools/build-anchors.sh put meld-ref and meldc-ref (default
# $MELD_ANCHORS, else $TMPDIR/anchors); --suite: the established VM's source tree, for its
# benchs/progs (default ANCHORS/src/meld, which build-anchors.sh exports); --runs (default 3),
# --modes, --json and --compile-timeout go to compare.py; --only keeps the named programs (8queens-12,
# belief-propagation-50, new-heat-transfer-80, pagerank-movies, pagerank-recipes, shortest-path,
# heat-transfer, n-queens, pagerank, belief-propagation). The B2 programs are generated at their
# default sizes by bench/meld/run-b2.sh --generate-only (into build/bench/meld).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # usage
anchors="${MELD_ANCHORS:-${TMPDIR:-/tmp}/anchors}"
suite="" runs=3 modes="" json=0 only="" compile_timeout=""
while [ $# -gt 0 ]; do
  case "$1" in
    --anchors) anchors="$2"; shift 2 ;;
    --suite) suite="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --modes) modes="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    --compile-timeout) compile_timeout="$2"; shift 2 ;;
    --json) json=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "table.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
suite="${suite:-$anchors/src/meld}"
progs="$suite/benchs/progs"
[ -d "$progs" ] || { echo "table.sh: no $progs (give --suite, or run build-anchors.sh)" >&2; exit 2; }
# The suite's programs and the arguments its benchs/args does not give (the pagerank bound).
# (new-heat-transfer-80 takes its arguments and -n from the suite's args file, read by compare.py.)
declare -A suite_args=([8queens-12]="" [belief-propagation-50]="" [new-heat-transfer-80]=""
                       [pagerank-movies]="0.00001" [pagerank-recipes]="0.00001")
specs=()
wanted() { [ -z "$only" ] || [[ " $only " == *" $1 "* ]]; }
for p in 8queens-12 belief-propagation-50 new-heat-transfer-80 pagerank-movies pagerank-recipes; do
  wanted "$p" || continue
  [ -f "$progs/$p.meld" ] || { echo "table.sh: $progs/$p.meld is missing" >&2; exit 1; }
  a="${suite_args[$p]}"
  specs+=("$progs/$p.meld${a:+=$a}")
done
for p in shortest-path heat-transfer n-queens pagerank belief-propagation; do
  wanted "$p" || continue
  specs+=("$("$here/../meld/run-b2.sh" --generate-only --only "$p")")
done
[ ${#specs[@]} -gt 0 ] || { echo "table.sh: --only kept no program" >&2; exit 2; }
extra=()
[ -n "$modes" ] && extra+=(--modes "$modes")
[ "$json" = 1 ] && extra+=(--json)
[ -n "$compile_timeout" ] && extra+=(--compile-timeout "$compile_timeout")
exec python3 "$here/compare.py" --anchors "$anchors" --runs "$runs" "${extra[@]}" "${specs[@]}"
