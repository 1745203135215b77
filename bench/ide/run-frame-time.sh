#!/usr/bin/env bash
# The 3D view's frame time under Xvfb's software renderer (Mesa llvmpipe), at 1k, 10k and 100k
# Blinky Blocks: vsim-ide --screenshot --frame-time N draws N frames offscreen, each as while
# running (the blocks' instance data uploaded, then drawn, then glFinish), and prints the mean.
#   bench/ide/run-frame-time.sh [--frames N] [--size WxH]
# VSIM_IDE=/path/to/vsim-ide selects the program (default build/release/ide/vsim-ide).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # median, usage
repo="$(cd "$here/../.." && pwd)"
ide="${VSIM_IDE:-$repo/build/release/ide/vsim-ide}"
workdir="$repo/build/bench/ide"
frames=20 size=1280x800
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames="$2"; shift 2 ;;
    --size) size="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-frame-time.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$ide" ] || { echo "run-frame-time.sh: vsim-ide not found at $ide (build it, or set VSIM_IDE=...)" >&2; exit 1; }
command -v xvfb-run > /dev/null || { echo "run-frame-time.sh: xvfb-run is needed (Debian package xvfb)" >&2; exit 1; }
mkdir -p "$workdir"
source "$here/box-world.sh"
world() {  # world NAME X Y Z: the file's path
  box_world "$workdir/$1.xml" "$2" "$3" "$4"
  echo "$workdir/$1.xml"
}
printf "%-8s %9s %10s\n" blocks size ms/frame
for spec in "1k 10 10 10" "10k 100 100 1" "100k 100 100 10"; do
  set -- $spec
  w="$(world "frames-$1" "$2" "$3" "$4")"
  out="$(xvfb-run -a -s "-screen 0 1600x1200x24" "$ide" "$w" --program "$repo/bench/meld-robots/gradient.meld" \
          --tap 0@1ms --screenshot "$workdir/frames-$1.png" --size "$size" --frame-time "$frames" --quiet 2>&1)"
  ms="$(sed -n 's/^frame time: \([0-9.]*\) ms.*/\1/p' <<< "$out")"
  [ -n "$ms" ] || { echo "run-frame-time.sh: no figure from vsim-ide: $out" >&2; exit 1; }
  blocks=$(($2 * $3 * $4))
  printf "%-8s %9s %10s\n" "$blocks" "$size" "$ms"
done
