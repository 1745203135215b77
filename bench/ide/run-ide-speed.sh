#!/usr/bin/env bash
# "As fast as possible" in vsim-ide's window against headless vsim, on the same run: the B3
# gradient on a Blinky Blocks box (default 100x100x10 = 100k blocks; --quick: 40x40x10), under
# Xvfb. Prints both events/s and their ratio (goal: the IDE at least half of headless) and checks
# that the two fingerprints are the same; K runs (default 5), each headless then in the window,
# and the medians (the VM's timings vary by tens of percent between runs of one second).
#   bench/ide/run-ide-speed.sh [--quick] [--runs K]
# IDE_SPEED=/path/to/ide_speed selects the program (default build/release/bench/ide/ide_speed).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # median, usage
repo="$(cd "$here/../.." && pwd)"
bin="${IDE_SPEED:-$repo/build/release/bench/ide/ide_speed}"
workdir="$repo/build/bench/ide"
x=100 y=100 z=10 runs=5
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) x=40 y=40; shift ;;
    --runs) runs="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-ide-speed.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$bin" ] || { echo "run-ide-speed.sh: ide_speed not found at $bin (build it, or set IDE_SPEED=...)" >&2; exit 1; }
mkdir -p "$workdir"
w="$workdir/speed-$x-$y-$z.xml"
source "$here/box-world.sh"
box_world "$w" "$x" "$y" "$z"
echo "world: $x x $y x $z Blinky Blocks, program bench/meld-robots/gradient.meld, tap 0@1ms, $runs runs"
heads="" ides="" ratios=""
for ((r = 0; r < runs; ++r)); do
  out="$(xvfb-run -a -s "-screen 0 1600x1200x24" "$bin" "$w" --program "$repo/bench/meld-robots/gradient.meld" \
           --tap 0@1ms 2>&1)" || { echo "run-ide-speed.sh: ide_speed failed: $out" >&2; exit 1; }
  grep -q "fingerprints.* same" <<< "$out" || { echo "run-ide-speed.sh: fingerprints differ: $out" >&2; exit 1; }
  heads+="$(sed -n 's/^headless .* \([0-9]*\) events\/s.*/\1/p' <<< "$out")"$'\n'
  ides+="$(sed -n 's/^ide, fastest .* \([0-9]*\) events\/s.*/\1/p' <<< "$out")"$'\n'
  ratios+="$(sed -n 's/^ide \/ headless *//p' <<< "$out")"$'\n'
  [ "$r" = 0 ] && grep -E "^(events|fingerprints)" <<< "$out"
done
printf "headless events/s (median)   %s\n" "$(grep . <<< "$heads" | median)"
printf "ide fastest events/s         %s\n" "$(grep . <<< "$ides" | median)"
printf "ide / headless (median)      %s   (runs: %s)\n" "$(grep . <<< "$ratios" | median)" "$(grep . <<< "$ratios" | tr '\n' ' ')"
