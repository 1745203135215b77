#!/usr/bin/env bash
# Benchmark B5 (compile costs): meldc's time and peak memory writing bytecode and writing native
# code (a shared object), and the JIT's start-up in meld, on the largest example program
# (examples/meld/, by size; compiled with --robots, as vsim runs it) and on a generated program of
# many rules (gen_rules.py). Medians of RUNS runs; load_s and jit_load_s are `meld --stats`' load time
# of the bytecode without and with --jit (the difference is the JIT's start-up).
#   bench/native/run-b5.sh [--runs K] [--rules N]
# MELDC and MELD select the binaries (default: build/release/meldc/meldc, build/release/apps/meld/meld).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # median, usage
repo="$(cd "$here/../.." && pwd)"
meldc="${MELDC:-$repo/build/release/meldc/meldc}"
meld="${MELD:-$repo/build/release/apps/meld/meld}"
work="$repo/build/bench/native"
runs=3 rules=10000
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --rules) rules="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-b5.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ && "$rules" =~ ^[1-9][0-9]*$ ]] || { echo "run-b5.sh: --runs and --rules take positive integers" >&2; exit 2; }
for b in "$meldc" "$meld"; do [ -x "$b" ] || { echo "run-b5.sh: $b not found (build the release preset)" >&2; exit 1; }; done
command -v /usr/bin/time > /dev/null || { echo "run-b5.sh: /usr/bin/time is needed (Debian package time)" >&2; exit 1; }
mkdir -p "$work"

measure() {  # median "wall_s peak_MB" of RUNS runs of the command
  local t m ts="" ms=""
  for ((r = 0; r < runs; ++r)); do
    /usr/bin/time -o "$work/last.time" -f "%e %M" "$@" > /dev/null 2> "$work/last.err" \
      || { echo "run-b5.sh: failed: $*" >&2; cat "$work/last.err" >&2; exit 1; }
    read -r t m < "$work/last.time"
    ts+="$t"$'\n'; ms+="$m"$'\n'
  done
  echo "$(printf "%s" "$ts" | median) $(printf "%s" "$ms" | median | awk '{printf "%.1f", $1 / 1024}')"
}
load_s() {  # median "load s" of `meld ARGS --stats`
  local ls=""
  for ((r = 0; r < runs; ++r)); do
    ls+="$("$meld" "$@" --stats 2>&1 >/dev/null | sed -n 's/^load s: //p')"$'\n'
  done
  printf "%s" "$ls" | median
}

example="$(ls -S "$repo"/examples/meld/*.meld | head -1)"
python3 "$here/gen_rules.py" --rules "$rules" -o "$work/rules-$rules.meld"
printf "%-28s %6s %10s %9s %10s %9s %10s %10s %11s\n" program rules bc_s bc_MB native_s native_MB so_KB load_s jit_load_s
for entry in "robots:$example" "plain:$work/rules-$rules.meld"; do
  kind="${entry%%:*}" file="${entry#*:}" flags=()
  [ "$kind" = robots ] && flags=(--robots)
  name="$(basename "$file" .meld)"
  read -r bc_s bc_mb < <(measure "$meldc" "${flags[@]}" "$file" -o "$work/$name.mbc")
  read -r so_s so_mb < <(measure "$meldc" "${flags[@]}" --emit=native "$file" -o "$work/$name.so")
  count="$(grep -c -e '-o' "$file" || true)"
  size_kb="$(du -k "$work/$name.so" | cut -f1)"
  printf "%-28s %6s %10s %9s %10s %9s %10s %10s %11s\n" "$name" "$count" "$bc_s" "$bc_mb" "$so_s" "$so_mb" "$size_kb" \
    "$(load_s "$work/$name.mbc")" "$(load_s "$work/$name.mbc" --jit)"
done
