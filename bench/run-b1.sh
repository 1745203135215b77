#!/usr/bin/env bash
# Benchmark B1 (brownian-flood): runs every size RUNS times and prints the median of each figure.
#   bench/run-b1.sh [--runs K] [--until T] [--sizes "7000 100000 1000000"] [--fes ladder] [--epidemic] [--json]
# Sizes default to 7k, 100k, 1M, plus 2M when the machine has at least 2 GB of memory available.
# Build first: cmake --preset release && cmake --build build/release --target brownian-flood
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/common.sh"  # median, usage
bin="${BROWNIAN_FLOOD:-$here/../build/release/bench/brownian-flood/brownian-flood}"
runs=3 until=600s fes=ladder json=0 sizes="" epidemic=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --until) until="$2"; shift 2 ;;
    --sizes) sizes="$2"; shift 2 ;;
    --fes) fes="$2"; shift 2 ;;
    --json) json=1; shift ;;
    --epidemic) epidemic=(--epidemic); shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-b1.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$bin" ] || { echo "run-b1.sh: $bin not built (cmake --build build/release --target brownian-flood)" >&2; exit 1; }
if [ -z "$sizes" ]; then
  sizes="7000 100000 1000000"
  avail_kb=$(awk '/MemAvailable/ {print $2}' /proc/meminfo)
  [ "$avail_kb" -ge 2000000 ] && sizes="$sizes 2000000"
fi

field() { sed -n "s/.*\"$1\":\"\{0,1\}\([^,\"}]*\).*/\1/p"; }

[ "$json" = 1 ] || printf "%-9s %6s %14s %9s %11s %10s %9s %12s %9s  %s\n" blocks runs events wall_s Mevents/s rss_MB B/block \
  messages reached fingerprint
for n in $sizes; do
  out=""
  for ((r = 0; r < runs; ++r)); do
    out+="$("$bin" --blocks "$n" --until "$until" --fes "$fes" "${epidemic[@]}" --json --no-progress)"$'\n'
  done
  fps=$(printf "%s" "$out" | field fingerprint | sort -u)
  [ "$(printf "%s\n" "$fps" | wc -l)" = 1 ] || { echo "run-b1.sh: runs of $n blocks differ: $fps" >&2; exit 1; }
  events=$(printf "%s" "$out" | field events | head -1)
  wall=$(printf "%s" "$out" | field wall_s | median)
  eps=$(printf "%s" "$out" | field events_per_s | median)
  rss=$(printf "%s" "$out" | field peak_rss_kb | median)
  bpb=$(printf "%s" "$out" | field bytes_per_block | median)
  messages=$(printf "%s" "$out" | field messages_sent | head -1)
  flooded=$(printf "%s" "$out" | field flooded | head -1)
  reached=$(printf "%s" "$out" | head -1 | sed -n 's/.*"reached":\(\[[^"]*\]\),"fingerprint".*/\1/p')
  if [ "$json" = 1 ]; then
    printf '{"blocks":%s,"runs":%s,"until":"%s","fes":"%s","epidemic":%s,"events":%s,"wall_s":%s,"events_per_s":%s,"peak_rss_kb":%s,"bytes_per_block":%s,"messages_sent":%s,"flooded":%s,"reached":%s,"fingerprint":"%s"}\n' \
      "$n" "$runs" "$until" "$fes" "$([ ${#epidemic[@]} -gt 0 ] && echo true || echo false)" "$events" "$wall" "$eps" \
      "$rss" "$bpb" "$messages" "$flooded" "$reached" "$fps"
  else
    printf "%-9s %6s %14s %9.2f %11.2f %10.1f %9.0f %12s %9s  %s\n" "$n" "$runs" "$events" "$wall" \
      "$(awk -v e="$eps" 'BEGIN{print e/1e6}')" "$(awk -v r="$rss" 'BEGIN{print r/1024}')" "$bpb" "$messages" "$flooded" "$fps"
    echo "          reached over time (simulated s, blocks): $reached"
  fi
done
