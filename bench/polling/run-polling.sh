#!/usr/bin/env bash
# Polling BlockCodes (simcore/abi/include/simcore/blockcode_polling.h): memory and time of the same
# program written both ways, the wave of examples/c/wave_events.c and wave_polling.c, on a box of
# Blinky Blocks (block 0 starts a wave; each block colours itself, waits 100 ms, passes it on).
#   bench/polling/run-polling.sh [--size "100 100 10"] [--runs K]
# Prints per style: events, simulated and wall seconds, peak RSS, bytes per block (peak RSS / N),
# and what the polling style adds per block (its stack, coroutine record and inbox, as far as they
# are touched); checks that both styles give the same fingerprint and the same trace of colours.
# Build first: cmake --preset release && cmake --build build/release --target vsim wave_events wave_polling
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # median, usage
build="${BUILD:-$here/../../build/release}"
size="100 100 10" runs=3
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-polling.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
vsim="$build/apps/vsim/vsim"
for f in "$vsim" "$build/blockcodes/wave_events.so" "$build/blockcodes/wave_polling.so"; do
  [ -e "$f" ] || { echo "run-polling.sh: $f not built (see --help)" >&2; exit 1; }
done
read -r sx sy sz <<<"$size"
n=$((sx * sy * sz))
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat >"$work/box.xml" <<XML
<?xml version="1.0"?>
<world gridSize="$sx,$sy,$sz" target="blinkyblocks" seed="1">
  <blockList blockSize="40,40,40"><blocksBox origin="0,0,0" size="$sx,$sy,$sz"/></blockList>
</world>
XML
echo "wave on a ${sx}x${sy}x${sz} box of Blinky Blocks ($n blocks), $runs runs each, medians"
printf '%-8s %12s %10s %8s %10s %12s  %s\n' style events "sim s" "wall s" "RSS MB" bytes/block fingerprint
for style in events polling; do
  walls="" rss=""
  for ((r = 0; r < runs; r++)); do
    /usr/bin/time -f "%e %M" -o "$work/time" "$vsim" "$work/box.xml" --code "$build/blockcodes/wave_$style.so" \
      --no-progress --trace kinds=color --trace-file "$work/trace-$style" >"$work/out-$style"
    read -r wall kb <"$work/time"
    walls="$walls$wall"$'\n' rss="$rss$kb"$'\n'
  done
  events=$(sed -n 's/^  events  *\([0-9]*\)$/\1/p' "$work/out-$style")
  sim=$(sed -n 's/^  simulated time *\([0-9.]*\) s/\1/p' "$work/out-$style")
  fp=$(sed -n 's/^  fingerprint *//p' "$work/out-$style")
  kb=$(printf '%s' "$rss" | median)
  printf '%-8s %12s %10.3f %8.2f %10.1f %12.0f  %s\n' "$style" "$events" "$sim" "$(printf '%s' "$walls" | median)" \
    "$(echo "$kb / 1024" | bc -l)" "$(echo "$kb * 1024 / $n" | bc -l)" "$fp"
  eval "fp_$style=$fp kb_$style=$kb"
done
echo "the polling style's own cost: $(echo "($kb_polling - $kb_events) * 1024 / $n" | bc) bytes per block of peak RSS"
[ "$fp_events" = "$fp_polling" ] || { echo "run-polling.sh: the two styles ran differently" >&2; exit 1; }
cmp -s "$work/trace-events" "$work/trace-polling" || { echo "run-polling.sh: the colour traces differ" >&2; exit 1; }
echo "same fingerprint and colour trace in both styles"
