#!/usr/bin/env bash
# Benchmark B3 (Meld on simulated robots): the distance gradient from a tapped block and the max-id
# leader election, as Meld programs run by the VM on every block (vsim --program), on a Blinky
# Blocks box of 100x100x10 and on a Catoms 3D ensemble of about 100k (47x47x46 FCC cells).
#   bench/meld-robots/run-b3.sh [--quick] [--runs K] [--json]
# VSIM=/path/to/vsim selects the simulator (default build/release/apps/vsim/vsim). Prints, per world
# and program: blocks, events, simulated time, wall s, events/s, facts derived, facts/s, peak RSS,
# bytes per block (peak RSS / blocks, the whole process: VM state, world, code) and the fingerprint.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # median, usage
repo="$(cd "$here/../.." && pwd)"
vsim="${VSIM:-$repo/build/release/apps/vsim/vsim}"
workdir="$repo/build/bench/meld-robots"
runs=3 quick=0 json=0
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1; shift ;;
    --runs) runs="$2"; shift 2 ;;
    --json) json=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-b3.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$vsim" ] || { echo "run-b3.sh: vsim not found at $vsim (build it, or set VSIM=...)" >&2; exit 1; }
command -v /usr/bin/time > /dev/null || { echo "run-b3.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 1; }
mkdir -p "$workdir"

world() {  # world NAME TARGET X Y Z: one blocksBox of X*Y*Z blocks
  local f="$workdir/$1.xml"
  cat > "$f" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<world gridSize="$(($3 + 2)),$(($4 + 2)),$(($5 + 2))" target="$2" seed="1">
  <blockList color="128,128,128">
    <blocksBox origin="1,1,1" size="$3,$4,$5"/>
  </blockList>
</world>
XML
  echo "$f"
}
if [ "$quick" = 1 ]; then
  worlds="$(world blinky-b3 blinkyblocks 10 10 4) $(world catoms3d-b3 catoms3d 8 8 8)"
else
  worlds="$(world blinky-b3 blinkyblocks 100 100 10) $(world catoms3d-b3 catoms3d 47 47 46)"
fi

field() { sed -n "s/^  $1 *\(.*\)$/\1/p" | head -1; }

[ "$json" = 1 ] || printf "%-12s %-9s %7s %11s %12s %7s %9s %12s %9s %7s %8s %9s  %s\n" \
  world program blocks events sim_time wall_s Mev/s facts_derived Mfacts/s rss_MB B/block VM_B/block fingerprint
for w in $worlds; do
  for prog in gradient leader; do
    walls="" rsss="" fp="" events="" facts="" simt="" blocks=""
    for ((r = 0; r < runs; ++r)); do
      log="$workdir/$(basename "$w" .xml)-$prog.run$r.log"
      /usr/bin/time -f "peak_kb %M" "$vsim" "$w" --program "$here/$prog.meld" --tap 0@1ms --no-progress \
        > "$log" 2>&1 || { echo "run-b3.sh: vsim failed, see $log" >&2; tail -5 "$log" >&2; exit 1; }
      walls+="$(field 'wall time' < "$log" | awk '{print $1}')"$'\n'
      rsss+="$(sed -n 's/^peak_kb //p' "$log")"$'\n'
      f="$(field fingerprint < "$log")"
      [ -z "$fp" ] || [ "$fp" = "$f" ] || echo "run-b3.sh: fingerprints differ between runs ($fp, $f)" >&2
      fp="$f"; events="$(field events < "$log")"; facts="$(field 'facts derived' < "$log")"
      simt="$(field 'simulated time' < "$log" | awk '{print $1}')"; blocks="$(field blocks < "$log")"
      vmb="$(field 'vm bytes' < "$log")"
    done
    wall="$(printf "%s" "$walls" | median)"; rss="$(printf "%s" "$rsss" | median)"
    name="$(basename "$w" .xml)"
    evs="$(awk -v e="$events" -v w="$wall" 'BEGIN{printf "%.2f", e / w / 1e6}')"
    fps="$(awk -v f="$facts" -v w="$wall" 'BEGIN{printf "%.2f", f / w / 1e6}')"
    rssmb="$(awk -v k="$rss" 'BEGIN{printf "%.1f", k / 1024}')"
    bpb="$(awk -v k="$rss" -v b="$blocks" 'BEGIN{printf "%.0f", k * 1024 / b}')"
    vmbpb="$(awk -v v="$vmb" -v b="$blocks" 'BEGIN{printf "%.0f", v / b}')"
    if [ "$json" = 1 ]; then
      printf '{"world":"%s","program":"%s","blocks":%s,"events":%s,"simulated_s":%s,"wall_s":%s,"facts_derived":%s,"peak_rss_mb":%s,"bytes_per_block":%s,"vm_bytes_per_block":%s,"fingerprint":"%s"}\n' \
        "$name" "$prog" "$blocks" "$events" "$simt" "$wall" "$facts" "$rssmb" "$bpb" "$vmbpb" "$fp"
    else
      printf "%-12s %-9s %7s %11s %12s %7.2f %9s %12s %9s %7s %8s %9s  %s\n" "$name" "$prog" "$blocks" "$events" \
        "$simt" "$wall" "$evs" "$facts" "$fps" "$rssmb" "$bpb" "$vmbpb" "$fp"
    fi
  done
done
