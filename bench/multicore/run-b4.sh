#!/usr/bin/env bash
# Benchmark B4 (multicore scaling): the five B2 programs (bench/meld/) with `meld -j N`, RUNS
# times per thread count; prints per program and thread count the median wall seconds, speedup
# over -j 1, efficiency (speedup / N), facts derived (they differ between thread counts for the
# programs whose result depends on the schedule: heat-transfer, n-queens), Mfacts/s and the
# threads' busy and steal shares; writes one profile per program and thread count (a separate,
# untimed run) as Chrome trace JSON. `vsim-ide --profile-view F.j1.json --profile-view F.j2.json`
# shows one program's profiles with their speedup table.
#   bench/multicore/run-b4.sh [--threads "1 2"] [--runs K] [--quick] [--only "prog1 prog2"]
#                             [--profiles DIR]
# Default thread counts: 1 and every power of two up to the number of cores. MELD=/path/to/meld
# selects the binary (default: build/release/apps/meld/meld). Profiles go to
# build/bench/multicore/ (or --profiles DIR).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
meld="${MELD:-$repo/build/release/apps/meld/meld}"
profiles="$repo/build/bench/multicore"
runs=3 quick="" only="" threads=""

. "$here/common.sh"
while [ $# -gt 0 ]; do
  case "$1" in
    --threads) threads="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --quick) quick="--quick"; shift ;;
    --only) only="$2"; shift 2 ;;
    --profiles) profiles="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-b4.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "run-b4.sh: --runs needs a positive integer" >&2; exit 2; }
[ -x "$meld" ] || { echo "run-b4.sh: no meld binary at $meld (build the release preset first)" >&2; exit 1; }
if [ -z "$threads" ]; then
  cores=$(nproc)
  threads="1"
  for ((t = 2; t <= cores; t *= 2)); do threads="$threads $t"; done
fi
for t in $threads; do
  [[ "$t" =~ ^[1-9][0-9]*$ ]] || { echo "run-b4.sh: bad thread count '$t'" >&2; exit 2; }
done
mkdir -p "$profiles"

mapfile -t files < <(b2_programs "$repo" "$quick" "$only")


echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), meld: $meld"
printf '| %-20s | %7s | %8s | %7s | %10s | %13s | %8s | %7s | %7s |\n' program threads "wall s" speedup efficiency "facts derived" "Mfacts/s" "busy %" "steal %"
printf '|%s|\n' "---|---:|---:|---:|---:|---:|---:|---:|---:"
status=0
for file in "${files[@]}"; do
  name=$(basename "$file" .meld)
  program=${name%%_*}
  base=""
  for t in $threads; do
    walls=() log="$profiles/$name.j$t.log"
    for ((r = 1; r <= runs; r++)); do
      if ! "$meld" "$file" -j "$t" --stats > /dev/null 2> "$log"; then
        echo "run-b4.sh: $program -j $t failed (see $log)" >&2
        status=1
        continue 2
      fi
      walls+=("$(field "wall s" "$log")")
    done
    wall=$(printf '%s\n' "${walls[@]}" | median)
    derived=$(field "facts derived" "$log")
    [ -z "$base" ] && base=$wall
    # busy and steal shares: averages over the threads of the last run's table (-j 1: the VM is busy throughout)
    read -r busy steal < <(awk '/^thread +busy/ { on = 1; next } on && NF >= 12 { b += $2; s += $12; n++ }
        END { if (n) printf "%.1f %.1f\n", b / n, s / n; else print "100.0 0.0" }' "$log")
    "$meld" "$file" -j "$t" --profile "$profiles/$name.j$t.json" > /dev/null 2>&1 || true
    awk -v p="$program" -v t="$t" -v w="$wall" -v b="$base" -v d="$derived" -v busy="$busy" -v steal="$steal" 'BEGIN {
        s = (w > 0) ? b / w : 0
        printf "| %-20s | %7d | %8.3f | %7.2f | %10.2f | %13d | %8.2f | %7s | %7s |\n", p, t, w, s, s / t, d, (w > 0 ? d / w / 1e6 : 0), busy, steal }'
  done
done
echo "profiles: $profiles/*.json (open in https://ui.perfetto.dev)"
exit $status
