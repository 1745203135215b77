#!/usr/bin/env bash
# suite-run.sh MODE NAME.meld [-- ARGS]: runs one program of the established toolchain's test
# suite on this toolchain and prints its dump; the command prefix suite.sh gives
# ../shared/tools/meld-conformance.sh. MODE: bc (meld NAME.meld), jit (--jit), so (meldc
# --emit=native, then meld NAME.so), j2 (-j 2); ref1 and ref2: the established toolchain in
# $MELD_ANCHORS (build-anchors.sh's meldc-ref, then meld-ref -c th1 or th2). The suite's MELD_ARGS
# (exported by the conformance script) may hold -n, the established VM's "no coordination": ours
# is --no-scheduling. MELD and MELDC name the binaries (default: this repository's build/release).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
meld="${MELD:-$repo/build/release/apps/meld/meld}"
meldc="${MELDC:-$repo/build/release/meldc/meldc}"
[ $# -ge 2 ] || { echo "usage: suite-run.sh bc|jit|so|j2|ref1|ref2 NAME.meld [-- ARGS]" >&2; exit 2; }
mode=$1 program=$2
shift 2
# -n, the established VM's "no coordination": ours is --no-scheduling (ref1/ref2 pass -n itself).
flags=() ref=()
for a in ${MELD_ARGS:-}; do
  [ "$a" = -n ] && flags+=(--no-scheduling) && ref+=(-n)
done
case "$mode" in
  bc) exec "$meld" "$program" --dump "${flags[@]}" "$@" ;;
  jit) exec "$meld" "$program" --dump --jit "${flags[@]}" "$@" ;;
  j2) exec "$meld" "$program" --dump -j 2 "${flags[@]}" "$@" ;;
  so)
    tmp="$(mktemp -d)"
    trap 'rm -rf "$tmp"' EXIT
    "$meldc" --emit=native --no-progress "$program" -o "$tmp/program.so" >&2
    "$meld" "$tmp/program.so" --dump "${flags[@]}" "$@"
    ;;
  ref1 | ref2)
    anchors="${MELD_ANCHORS:-${TMPDIR:-/tmp}/anchors}"
    [ -x "$anchors/meld-ref" ] && [ -x "$anchors/meldc-ref" ] ||
      { echo "suite-run.sh: no meld-ref/meldc-ref in $anchors (set MELD_ANCHORS)" >&2; exit 2; }
    tmp="$(mktemp -d)"
    trap 'rm -rf "$tmp"' EXIT
    MELDC_REF_NO_CPP=1 "$anchors/meldc-ref" "$program" "$tmp/program" > "$tmp/meldc.log" 2>&1 ||
      { cat "$tmp/meldc.log" >&2; exit 1; }
    "$anchors/meld-ref" -f "$tmp/program.m" -c "th${mode#ref}" "${ref[@]}" -d "$@"
    ;;
  *) echo "suite-run.sh: unknown mode '$mode'" >&2; exit 2 ;;
esac
