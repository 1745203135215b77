#!/usr/bin/env bash
# Packs what a thread-scaling run on another machine needs (a many-core machine lent by the
# `device` tool, which has neither compiler): the ten programs of bench/meld/README.md's table
# compiled by both toolchains, both VMs, GNU time, and run.sh, which runs bench/multicore/scaling.py
# there over them.
#   bench/multicore/scaling-kit.sh --anchors DIR [--kit DIR] [--only "name ..."] [--ref-timeout S]
# --anchors: where ../shared/tools/build-anchors.sh put meld-ref and meldc-ref (default
# $MELD_ANCHORS); --kit: the folder to fill (default build/scaling-kit, ignored by git, so a run
# names it in `carry`); --only: some of 8queens-12 belief-propagation-50 new-heat-transfer-80
# pagerank-movies pagerank-recipes shortest-path heat-transfer n-queens pagerank belief-propagation;
# --ref-timeout: seconds the established compiler may take per program (default 3600: it takes
# over half an hour on shortest-path here; three of the B2 programs it refuses). Compiled files are
# kept in build/bench/scaling and reused while newer than their source. Then, on the other machine:
#   bash build/scaling-kit/run.sh [THREADS [ROUNDS [BUDGET_S]]]   (defaults: 1,2,4,...,nproc 3 480)
# writes the log, lscpu and scaling.json to $OUT (or the kit's folder where OUT is unset).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # usage
repo="$(cd "$here/../.." && pwd)"
meld="${MELD:-$repo/build/release/apps/meld/meld}"
meldc="${MELDC:-$repo/build/release/meldc/meldc}"
anchors="${MELD_ANCHORS:-}" kit="$repo/build/scaling-kit" only="" ref_timeout=3600
cache="$repo/build/bench/scaling"
while [ $# -gt 0 ]; do
  case "$1" in
    --anchors) anchors="$2"; shift 2 ;;
    --kit) kit="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    --ref-timeout) ref_timeout="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "scaling-kit.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -n "$anchors" ] || { echo "scaling-kit.sh: --anchors DIR is needed (see --help)" >&2; exit 2; }
for tool in "$meld" "$meldc" "$anchors/meld-ref" "$anchors/meldc-ref"; do
  [ -x "$tool" ] || { echo "scaling-kit.sh: $tool is not an executable" >&2; exit 1; }
done
suite="$anchors/src/meld/benchs/progs"
[ -d "$suite" ] || { echo "scaling-kit.sh: no $suite (run build-anchors.sh)" >&2; exit 1; }
wanted() { [ -z "$only" ] || [[ " $only " == *" $1 "* ]]; }

# name -> source file, and the program arguments of the table (bench/compare/table.sh's).
declare -A source=() args=([new-heat-transfer-80]="0.0001 0.005" [pagerank-movies]="0.00001"
                           [pagerank-recipes]="0.00001")
for p in 8queens-12 belief-propagation-50 new-heat-transfer-80 pagerank-movies pagerank-recipes; do
  wanted "$p" && source[$p]="$suite/$p.meld"
done
for p in shortest-path heat-transfer n-queens pagerank belief-propagation; do
  wanted "$p" && source[$p]="$("$repo/bench/meld/run-b2.sh" --generate-only --only "$p")"
done
[ ${#source[@]} -gt 0 ] || { echo "scaling-kit.sh: --only kept no program" >&2; exit 2; }

mkdir -p "$cache" "$kit"
rm -rf "$kit/programs"
mkdir -p "$kit/programs"
specs=()
for p in "${!source[@]}"; do
  src="${source[$p]}"
  dir="$(dirname "$src")"
  # Includes are found from the program's own folder, as the established VM's suite expects.
  if [ ! "$cache/$p.mbc" -nt "$src" ]; then
    (cd "$dir" && "$meldc" "$src" -o "$cache/$p.mbc")
  fi
  if [ ! "$cache/$p.m" -nt "$src" ] && [ ! "$cache/$p.refused" -nt "$src" ]; then
    echo "scaling-kit.sh: compiling $p with the established compiler (may take long)" >&2
    if (cd "$dir" && MELDC_REF_NO_CPP=1 timeout "$ref_timeout" "$anchors/meldc-ref" "$src" "$cache/$p.m" \
          > "$cache/$p.ref.log" 2>&1); then
      rm -f "$cache/$p.refused"
    else
      touch "$cache/$p.refused"
      echo "scaling-kit.sh: the established compiler refused $p ($(tail -1 "$cache/$p.ref.log"))" >&2
    fi
  fi
  cp "$cache/$p.mbc" "$kit/programs/"
  [ -f "$cache/$p.m" ] && [ ! -f "$cache/$p.refused" ] && cp "$cache/$p.m" "$kit/programs/"
  specs+=("programs/$p${args[$p]:+=${args[$p]}}")
done
(cd "$kit" && tar cf - programs | xz -T0 -6 > programs.tar.xz && rm -rf programs)
cp "$meld" "$kit/meld"
cp "$(readlink -f "$anchors/meld-ref")" "$kit/meld-ref"
time_bin="$(type -P time || true)"
[ -n "$time_bin" ] && cp "$time_bin" "$kit/gnu-time"
printf '%s\n' "${specs[@]}" > "$kit/programs.txt"
cp "$here/scaling-run.sh" "$kit/run.sh"
du -sh "$kit" | sed 's/\t.*//' | xargs echo "scaling-kit.sh: kit ready in $kit, size"
