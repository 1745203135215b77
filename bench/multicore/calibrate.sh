#!/usr/bin/env bash
# Calibrates the multicore target's chip (vsim --target multicore) on this machine and checks its
# predictions: runs the five B2 programs (bench/meld/) with `meld -j 1` and `meld -j 2`, RUNS
# times each, fits the core costs to the median runs (fit_costs.py), then predicts each program's
# -j 2 speedup on a simulated 2-core chip with those costs and prints it next to the measured one
# (the median, over the RUNS pairs of runs, of the -j 1 wall over the -j 2 wall).
# With --curve, also the predicted speedup of every program on 1 to 256 cores.
#   bench/multicore/calibrate.sh [--runs K] [--quick] [--only "prog1 prog2"] [--curve]
#                                [--costs SPEC]   (skip the measurements and the fit: use SPEC)
#                                [--topology mesh|ring|full]
# MELD, VSIM and MELDC select the binaries (default: build/release/...). Logs go to
# build/bench/multicore/calibration/.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
meld="${MELD:-$repo/build/release/apps/meld/meld}"
vsim="${VSIM:-$repo/build/release/apps/vsim/vsim}"
meldc="${MELDC:-$repo/build/release/meldc/meldc}"
logs="$repo/build/bench/multicore/calibration"
runs=3 quick="" only="" curve="" costs="" topology=mesh

. "$here/common.sh"
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --quick) quick="--quick"; shift ;;
    --only) only="$2"; shift 2 ;;
    --curve) curve=1; shift ;;
    --costs) costs="$2"; shift 2 ;;
    --topology) topology="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "calibrate.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "calibrate.sh: --runs needs a positive integer" >&2; exit 2; }
for b in "$meld" "$vsim" "$meldc"; do
  [ -x "$b" ] || { echo "calibrate.sh: no binary at $b (build the release preset first)" >&2; exit 1; }
done
mkdir -p "$logs"

mapfile -t sources < <(b2_programs "$repo" "$quick" "$only")
files=()
for src in "${sources[@]}"; do
  mbc="${src%.meld}.mbc"
  [ "$mbc" -nt "$src" ] || "$meldc" "$src" -o "$mbc"
  files+=("$mbc")
done

# Runs `meld FILE -j 1 --stats` and `-j 2` one after the other, RUNS times (the machine's speed
# drifts: a pair run close together gives a fairer ratio); keeps the pair whose ratio is the
# median as NAME.j1.log and NAME.j2.log.
measure() {
  local file=$1 name tmp
  name=$(basename "$file" .mbc)
  tmp=$(mktemp -d)
  for ((r = 1; r <= runs; r++)); do
    "$meld" "$file" -j 1 --stats > /dev/null 2> "$tmp/$r.j1.log"
    "$meld" "$file" -j 2 --stats > /dev/null 2> "$tmp/$r.j2.log"
    echo "$(field "wall s" "$tmp/$r.j1.log") $(field "wall s" "$tmp/$r.j2.log") $r"
  done | awk '{ print $1 / $2, $3 }' | sort -g | awk -v n="$runs" 'NR == int((n + 1) / 2) { print $2 }' | {
    read -r median
    cp "$tmp/$median.j1.log" "$logs/$name.j1.log"
    cp "$tmp/$median.j2.log" "$logs/$name.j2.log"
  }
  rm -rf "$tmp"
}

if [ -z "$costs" ]; then
  rm -f "$logs"/*.log
  for file in "${files[@]}"; do
    echo "calibrate.sh: measuring $(basename "$file" .mbc) ($runs pairs of runs at -j 1 and -j 2)" >&2
    measure "$file"
  done
  "$here/fit_costs.py" "$logs" | tee "$logs/fit.txt"
  costs=$(awk '/^--costs / { print $2 }' "$logs/fit.txt")
fi

echo
echo "predicted (a simulated 2-core $topology chip, --costs $costs) against measured -j 2 speedup:"
printf '| %-20s | %9s | %9s | %9s | %9s | %9s | %7s |\n' program "j1 s" "j2 s" measured "chip 1 ms" predicted "error"
printf '|%s|\n' "---|---:|---:|---:|---:|---:|---:"
for file in "${files[@]}"; do
  name=$(basename "$file" .mbc)
  program=${name%%_*}
  out=$("$vsim" --target multicore --program "$file" --cores 1,2 --topology "$topology" --costs "$costs")
  read -r chip1 predicted < <(awk '$1 == 1 && NF == 7 { t1 = $2 } $1 == 2 && NF == 7 { s = $3 } END { print t1, s }' <<< "$out")
  if [ -f "$logs/$name.j1.log" ] && [ -f "$logs/$name.j2.log" ]; then
    w1=$(field "wall s" "$logs/$name.j1.log") w2=$(field "wall s" "$logs/$name.j2.log")
    awk -v p="$program" -v w1="$w1" -v w2="$w2" -v c1="$chip1" -v s="$predicted" 'BEGIN {
      m = w1 / w2; printf "| %-20s | %9.3f | %9.3f | %9.2f | %9.3f | %9.2f | %+6.0f%% |\n", p, w1, w2, m, c1, s, 100 * (s - m) / m }'
  else
    printf '| %-20s | %9s | %9s | %9s | %9.3f | %9.2f | %7s |\n' "$program" - - - "$chip1" "$predicted" -
  fi
done

if [ -n "$curve" ]; then
  counts=1,2,4,8,16,32,64,128,256
  echo
  echo "predicted speedup on 1 to 256 cores ($topology, --costs $costs):"
  printf '| %-20s |' program
  for n in ${counts//,/ }; do printf ' %6s |' "$n"; done
  echo
  printf '|%s' "---"; for _ in ${counts//,/ }; do printf '|%s' "---:"; done; echo '|'
  for file in "${files[@]}"; do
    name=$(basename "$file" .mbc)
    printf '| %-20s |' "${name%%_*}"
    "$vsim" --target multicore --program "$file" --cores "$counts" --topology "$topology" --costs "$costs" |
      awk 'NF == 7 && $1 ~ /^[0-9]+$/ { printf " %6.2f |", $3 } END { print "" }'
  done
fi
