#!/usr/bin/env bash
# Runs one conformance case and compares its dump with the hand-derived golden file.
#
# usage: run_case.sh MELD_BINARY CASE_DIR NAME [THREADS [VSIM_BINARY]]
#
# Runs `MELD_BINARY NAME.meld --dump [-j THREADS] [-- ARGS]` inside CASE_DIR (ARGS: the single
# line of NAME.args, split on blanks, if that file exists) with a 20 s timeout, and compares
# standard output byte for byte with NAME.expected. Exit 0 on a match; otherwise a unified diff
# (expected -> actual) is printed and the exit status is non-zero.
#
# MELD_FLAGS (environment) adds options to the meld command line: `--jit` runs the case as native
# code, against the same golden. MELDC_NATIVE=MELDC_BINARY (environment) compiles the case with
# `MELDC_BINARY --emit=native` first and runs the shared object instead of NAME.meld.
#
# With VSIM_BINARY, the case runs on a simulated chip of THREADS cores instead (the multicore
# target: `VSIM_BINARY --target multicore --cores THREADS --program NAME.meld --dump --quiet`).
#
# With THREADS > 1, a case listed in threads.list (its result depends on the order nodes run in)
# is compared through its check instead, applied to both the golden and the output:
#   lines          the same lines in any order (write-string output interleaves)
#   shape          per node, the same predicates with the same number of facts (values may differ)
#   node:K         node K's section exactly
#   graph-shape:N  `shape` over the nodes below N, and one section per thread from N on (the
#                  thread nodes, §6.12)
#   sum:P          the same sum of the last argument of P's facts over all nodes
#   renumbered     the same lines in any order once node ids are masked (created nodes)
#
# The goldens are derived by hand from the language specification, so UPDATE_GOLDEN=1 never
# rewrites them; it only prints a note.
set -u

if [ "$#" -lt 3 ] || [ "$#" -gt 5 ]; then
  echo "usage: $0 MELD_BINARY CASE_DIR NAME [THREADS [VSIM_BINARY]]" >&2
  exit 2
fi

meld=$1
dir=$2
name=$3
threads=${4:-1}
vsim=${5:-}
here=$(cd "$(dirname "$0")" && pwd)

case "$meld" in
  /*) ;;
  *) meld=$(pwd)/$meld ;;
esac
case "$vsim" in
  /* | "") ;;
  *) vsim=$(pwd)/$vsim ;;
esac

if [ ! -d "$dir" ]; then
  echo "run_case: no case folder $dir" >&2
  exit 2
fi
cd "$dir" || exit 2

if [ ! -f "$name.meld" ] || [ ! -f "$name.expected" ]; then
  echo "run_case: $name.meld or $name.expected missing in $dir" >&2
  exit 2
fi

if [ "${UPDATE_GOLDEN:-0}" = "1" ]; then
  echo "run_case: note: UPDATE_GOLDEN=1 ignored; $name.expected is hand-derived from the specification and is never rewritten" >&2
fi

args=()
if [ -f "$name.args" ]; then
  read -r -a args < "$name.args" || true
fi
jobs=()
check=same
if [ "$threads" -gt 1 ]; then
  jobs=(-j "$threads")
  rel=$name
  [ "$(pwd)" != "$here" ] && rel=$(basename "$(pwd)")/$name
  listed=$(awk -v n="$rel" '$1 == n { print $2 }' "$here/threads.list")
  [ -n "$listed" ] && check=$listed
fi

# The facts of one node section after another: "NODE PRED" per fact line.
node_preds() { awk '/^[0-9]+$/ { node = $1; next } { p = $0; sub(/\(.*/, "", p); print node, p }'; }
# What a check keeps of a dump (standard input).
view() {
  local part
  IFS='+' read -r -a parts <<< "$check"
  for part in "${parts[@]}"; do
    case "$part" in
      same) cat ;;
      lines) sort ;;
      shape) node_preds | sort | uniq -c ;;
      node:*) awk -v k="${part#node:}" '/^[0-9]+$/ { on = ($1 == k) } on' ;;
      graph-shape:*)
        local below=${part#graph-shape:}
        node_preds | awk -v n="$below" '$1 < n' | sort | uniq -c
        ;;
      sum:*)
        awk -v p="${part#sum:}" 'index($0, p "(") == 1 || index($0, "!" p "(") == 1 {
            v = $0; sub(/\)$/, "", v); sub(/.*[(, ]/, "", v); s += v } END { print "sum", s + 0 }'
        ;;
      renumbered) sed -E 's/@[0-9]+/@N/g; s/^[0-9]+$/NODE/' | sort ;;
      *) echo "run_case: unknown check '$part' in threads.list" >&2; return 2 ;;
    esac < "$1"
  done
}

actual=$(mktemp "${TMPDIR:-/tmp}/meld-conf.$name.XXXXXX") || exit 2
errors=$(mktemp "${TMPDIR:-/tmp}/meld-conf.$name.err.XXXXXX") || { rm -f "$actual"; exit 2; }
trap 'rm -f "$actual" "$errors"' EXIT

program=$name.meld
if [ -n "${MELDC_NATIVE:-}" ]; then
  so=$(mktemp "${TMPDIR:-/tmp}/meld-conf.$name.XXXXXX.so") || exit 2
  trap 'rm -f "$actual" "$errors" "$so"' EXIT
  if ! "$MELDC_NATIVE" --emit=native "$name.meld" -o "$so" 2> "$errors"; then
    echo "run_case: $name: $MELDC_NATIVE --emit=native failed" >&2
    sed 's/^/  stderr: /' "$errors" >&2
    exit 1
  fi
  program=$so
fi
read -r -a flags <<< "${MELD_FLAGS:-}"
run=("$meld" "$program" --dump "${jobs[@]}" "${flags[@]}")
mode="-j $threads ${MELD_FLAGS:-}${MELDC_NATIVE:+ (native .so)}"
if [ -n "$vsim" ]; then
  run=("$vsim" --target multicore --cores "$threads" --program "$name.meld" --dump --quiet)
  mode="a $threads-core chip"
  meld=$vsim
fi
if [ "${#args[@]}" -gt 0 ]; then
  timeout 20 "${run[@]}" -- "${args[@]}" > "$actual" 2> "$errors"
else
  timeout 20 "${run[@]}" > "$actual" 2> "$errors"
fi
status=$?

if [ "$status" -eq 124 ]; then
  echo "run_case: $name: timed out after 20 s" >&2
fi
if [ "$status" -ne 0 ]; then
  echo "run_case: $name: $meld exited with status $status" >&2
  if [ -s "$errors" ]; then
    sed 's/^/  stderr: /' "$errors" >&2
  fi
fi

if [ "$check" != same ]; then
  # graph-shape:N also wants one section per thread from node N on.
  for part in ${check//+/ }; do
    case "$part" in
      graph-shape:*)
        sections=$(awk -v n="${part#graph-shape:}" '/^[0-9]+$/ && $1 >= n { c++ } END { print c + 0 }' "$actual")
        if [ "$sections" -ne "$threads" ]; then
          echo "run_case: $name: $sections thread node sections from node ${part#graph-shape:} on, expected $threads" >&2
          exit 1
        fi
        ;;
    esac
  done
  expected_view=$(view "$name.expected") || exit 2
  actual_view=$(view "$actual") || exit 2
  if [ "$expected_view" = "$actual_view" ] && [ "$status" -eq 0 ]; then
    exit 0
  fi
  echo "run_case: $name: with $mode, the check '$check' differs (threads.list)" >&2
  diff -u --label "$name.expected ($check)" --label "$name (actual, $check)" <(echo "$expected_view") <(echo "$actual_view")
  exit 1
fi

if cmp -s "$name.expected" "$actual"; then
  if [ "$status" -ne 0 ]; then
    exit 1
  fi
  exit 0
fi

echo "run_case: $name: dump differs from $name.expected" >&2
diff -u --label "$name.expected" --label "$name (actual)" "$name.expected" "$actual"
exit 1
