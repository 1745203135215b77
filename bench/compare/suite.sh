#!/usr/bin/env bash
# The established toolchain's test suite (its tests/progs, 107 programs, with the dumps it
# expects) on this toolchain, in every mode, through ../shared/tools/meld-conformance.sh.
#   bench/compare/suite.sh [--mirror GITDIR] [--modes "bc jit so j2"] [--anchors DIR] [--keep DIR]
# --mirror: a git mirror of the established VM's repository (the MELD_MIRROR of
# build-anchors.sh; default $MELD_MIRROR). Modes ref1 and ref2 run the established toolchain
# itself (its compiler, then its VM with -c th1 or th2) from --anchors DIR (build-anchors.sh's
# folder; default $MELD_ANCHORS, else $TMPDIR/anchors): what its own runs give, to set against
# ours (ref2 against j2). Each mode prints the conformance script's PASS/FAIL
# lines for the tests that did not pass and its "N passed, M failed" line. Under j2 the suite's own
# runner leaves out the programs of its tests/non_deterministic.exclude (their result is the
# schedule's): those failures are listed apart. --keep DIR keeps every output (DIR/MODE/NAME.out).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # usage
repo="$(cd "$here/../.." && pwd)"
conformance="$repo/../shared/tools/meld-conformance.sh"
mirror="${MELD_MIRROR:-}" modes="bc jit so j2" keep=""
export MELD_ANCHORS="${MELD_ANCHORS:-${TMPDIR:-/tmp}/anchors}"
while [ $# -gt 0 ]; do
  case "$1" in
    --mirror) mirror="$2"; shift 2 ;;
    --anchors) MELD_ANCHORS="$(cd "$2" && pwd)" || exit 2; shift 2 ;;
    --modes) modes="$2"; shift 2 ;;
    --keep) keep="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -n "$mirror" ] || { echo "suite.sh: --mirror GITDIR (or MELD_MIRROR) is needed" >&2; exit 2; }
[ -f "$conformance" ] || { echo "suite.sh: no $conformance" >&2; exit 2; }
gitdir="$mirror"; [ -d "$mirror/.git" ] && gitdir="$mirror/.git"
excluded="$(git --git-dir="$gitdir" show HEAD:tests/non_deterministic.exclude 2>/dev/null || true)"
status=0
for mode in $modes; do
  echo "== $mode"
  out="$(mktemp)"
  MELD_CONFORMANCE_OUT="${keep:+$keep/$mode}" bash "$conformance" "$gitdir" "$here/suite-run.sh $mode" > "$out"
  if [ "$mode" = j2 ] || [ "$mode" = ref2 ]; then
    grep -v '^PASS' "$out" | while read -r verdict name rest; do
      case "$verdict" in FAIL|ERROR) ;; *) echo "$verdict $name $rest"; continue ;; esac
      n="${name%:}"
      if grep -qx "$n" <<< "$excluded"; then echo "$verdict $n (non-deterministic in the suite's own runner) $rest"
      else echo "$verdict $n $rest"; fi
    done
  else
    grep -v '^PASS' "$out"
  fi
  tail -1 "$out" | grep -q ' 0 failed' || status=1
  rm -f "$out"
done
exit $status
