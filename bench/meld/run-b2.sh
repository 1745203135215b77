#!/usr/bin/env bash
# Benchmark B2 (Meld VM throughput): generates the five programs of bench/meld/, runs each with
# `meld FILE.meld --stats` RUNS times (one thread) and prints the medians.
#   bench/meld/run-b2.sh [--quick] [--json] [--runs K] [--only "prog1 prog2"]
#                        [--args PROG "GENERATOR OPTIONS"] [--meld-args "ARGS"]
#                        [--workdir DIR] [--generate-only] [--native]
# MELD=/path/to/meld selects the binary (default: build/release/apps/meld/meld in the repository),
# MELDC=/path/to/meldc the compiler (default: build/release/meldc/meldc). Each generated program is
# compiled once to bytecode (.mbc, kept next to it) and the runs load the bytecode, so the figures
# are the VM's own: wall s and peak RSS do not include the compiler front end.
# --quick: tiny sizes (smoke run). --args replaces the generator options of one program (repeatable,
# e.g. --args pagerank "--nodes 5000 --iterations 20"). --meld-args is added to every meld command
# (e.g. "-j 4"). Generated programs go to build/bench/meld/ (or --workdir) and are reused while
# their generator, program and options are unchanged. --generate-only writes them and stops.
# --native adds the native-code columns: each run is followed by the same program as a shared object
# (`meldc --emit=native`, `meld FILE.so`) and compiled in memory (`meld FILE.mbc --jit`), medians of
# their wall s (the run: the JIT compile is in meld's load time) and the speedups over the bytecode; the three dumps are
# compared byte for byte once per program (a difference fails the script).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../common.sh"  # median, usage
repo="$(cd "$here/../.." && pwd)"
meld="${MELD:-$repo/build/release/apps/meld/meld}"
meldc="${MELDC:-$repo/build/release/meldc/meldc}"
workdir="$repo/build/bench/meld"
runs=3 json=0 quick=0 only="" meld_args="" generate_only=0 native=0
declare -A user_args=()

programs="shortest-path heat-transfer n-queens pagerank belief-propagation"
declare -A default_args=(
  [shortest-path]="--nodes 100000 --degree 8"
  [heat-transfer]="--width 100 --epsilon 0.001"
  [n-queens]="--queens 13"
  [pagerank]="--nodes 20000 --degree 8 --iterations 100"
  [belief-propagation]="--width 128 --labels 5 --iterations 50"
)
declare -A quick_args=(
  [shortest-path]="--nodes 1000 --degree 4"
  [heat-transfer]="--width 10 --epsilon 0.01"
  [n-queens]="--queens 8"
  [pagerank]="--nodes 500 --degree 4 --iterations 5"
  [belief-propagation]="--width 8 --labels 3 --iterations 5"
)

while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1; shift ;;
    --json) json=1; shift ;;
    --runs) runs="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    --args) user_args[$2]="$3"; shift 3 ;;
    --meld-args) meld_args="$2"; shift 2 ;;
    --workdir) workdir="$2"; shift 2 ;;
    --generate-only) generate_only=1; shift ;;
    --native) native=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run-b2.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "run-b2.sh: --runs needs a positive integer" >&2; exit 2; }
[ -n "$only" ] || only="$programs"
for p in $only "${!user_args[@]}"; do
  [ -n "${default_args[$p]+x}" ] || { echo "run-b2.sh: unknown program '$p' (programs: $programs)" >&2; exit 2; }
done
if [ "$generate_only" = 0 ] && [ ! -x "$meld" ]; then
  echo "run-b2.sh: meld binary not found at $meld" >&2
  echo "  build it (cmake --preset release && cmake --build build/release) or set MELD=/path/to/meld" >&2
  exit 1
fi
if [ "$generate_only" = 0 ] && [ ! -x "$meldc" ]; then
  echo "run-b2.sh: meldc binary not found at $meldc (set MELDC=/path/to/meldc)" >&2
  exit 1
fi
command -v python3 > /dev/null || { echo "run-b2.sh: python3 is needed to generate the programs" >&2; exit 1; }
mkdir -p "$workdir"

gen_args() {  # the generator options of program $1
  if [ -n "${user_args[$1]+x}" ]; then echo "${user_args[$1]}"
  elif [ "$quick" = 1 ]; then echo "${quick_args[$1]}"
  else echo "${default_args[$1]}"; fi
}
size_label() {  # "--nodes 100000 --degree 8" -> "nodes=100000 degree=8"
  echo "$*" | sed -e 's/--\([a-z-]*\) \([^ -][^ ]*\|-[0-9][^ ]*\)/\1=\2/g' -e 's/^ *//'
}
generate() {  # generate program $1 with options $2, print the file name
  local p="$1" a="$2" tag out
  tag="$(size_label "$a" | tr -s ' ' '_' | tr -cd 'A-Za-z0-9_.=-')"
  out="$workdir/$p${tag:+_$tag}.meld"
  if [ ! -s "$out" ] || [ "$here/$p/gen.py" -nt "$out" ] || [ "$here/$p/$p.meld" -nt "$out" ] \
      || [ "$here/b2gen.py" -nt "$out" ]; then
    # shellcheck disable=SC2086
    python3 "$here/$p/gen.py" $a -o "$out.tmp" || { rm -f "$out.tmp"; return 1; }
    mv "$out.tmp" "$out"
  fi
  echo "$out"
}
statval() {  # value of the `--stats` line "$1: VALUE" in the text on stdin (last one wins)
  sed -n "s/^[[:space:]]*$1:[[:space:]]*\([-+0-9.eE]*\).*/\1/p" | tail -1
}
num_or_null() { if [ -n "$1" ]; then echo "$1"; else echo null; fi; }

# --native: the shared object of program $1 (source $2, bytecode $3), and the three dumps compared.
native_prepare() {
  local p="$1" file="$2" mbc="$3" so="${3%.mbc}.so" d
  if [ ! -s "$so" ] || [ "$file" -nt "$so" ] || [ "$meldc" -nt "$so" ]; then
    if ! "$meldc" --emit=native "$file" -o "$so" > "$workdir/$p.native.log" 2>&1; then
      echo "run-b2.sh: $p: meldc --emit=native failed (see $workdir/$p.native.log)" >&2; rm -f "$so"; return 1
    fi
  fi
  # shellcheck disable=SC2086
  for d in "$mbc" "$so" "$mbc --jit"; do "$meld" $d --dump $meld_args 2>/dev/null | md5sum; done > "$workdir/$p.dumps"
  if [ "$(sort -u "$workdir/$p.dumps" | wc -l)" != 1 ]; then
    echo "run-b2.sh: $p: the bytecode, .so and --jit dumps differ" >&2; return 1
  fi
}
native_wall() {  # wall s of `meld ARGS... --stats` for program $1
  local p="$1" log="$workdir/$1.native-run.log"
  shift
  "$meld" "$@" --stats > "$log" 2>&1 || { echo "run-b2.sh: $p: meld $* failed (see $log)" >&2; return 1; }
  statval "wall s" < "$log"
}

status=0
if [ "$json" = 0 ] && [ "$generate_only" = 0 ]; then
  printf "%-19s %-34s %4s %9s %13s %13s %10s %9s" program size runs wall_s facts_derived rules_fired Mfacts/s rss_MB
  [ "$native" = 1 ] && printf " %8s %8s %7s %7s" so_s jit_s so_x jit_x
  printf "\n"
fi
for p in $only; do
  a="$(gen_args "$p")"
  size="$(size_label "$a")"
  file="$(generate "$p" "$a")" || { echo "run-b2.sh: generating $p failed" >&2; status=1; continue; }
  if [ "$generate_only" = 1 ]; then echo "$file"; continue; fi
  mbc="${file%.meld}.mbc"
  if [ ! -s "$mbc" ] || [ "$file" -nt "$mbc" ] || [ "$meldc" -nt "$mbc" ]; then
    if ! "$meldc" "$file" -o "$mbc" > "$workdir/$p.meldc.log" 2>&1; then
      echo "run-b2.sh: $p: meldc failed (see $workdir/$p.meldc.log)" >&2; rm -f "$mbc"; status=1; continue
    fi
  fi
  walls="" rates="" rsss="" derived="" consumed="" sent="" fired="" failed=0 so_walls="" jit_walls=""
  if [ "$native" = 1 ] && ! native_prepare "$p" "$file" "$mbc"; then status=1; continue; fi
  for ((r = 0; r < runs; ++r)); do
    log="$workdir/$p.run$r.log"
    t0=$(date +%s.%N)
    # shellcheck disable=SC2086
    if ! "$meld" "$mbc" --stats $meld_args > "$log" 2>&1; then
      echo "run-b2.sh: $p: meld failed (see $log):" >&2; tail -5 "$log" >&2; failed=1; break
    fi
    t1=$(date +%s.%N)
    w="$(statval "wall s" < "$log")"
    [ -n "$w" ] || w="$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.3f", b - a}')"   # no stats line: outside time
    d="$(statval "facts derived" < "$log")"
    if [ -n "$derived" ] && [ "$d" != "$derived" ]; then
      echo "run-b2.sh: $p: facts derived differ between runs ($derived, $d)" >&2
    fi
    derived="$d"; consumed="$(statval "facts consumed" < "$log")"; sent="$(statval "facts sent" < "$log")"
    fired="$(statval "rules fired" < "$log")"
    walls+="$w"$'\n'
    if [ "$native" = 1 ]; then
      # shellcheck disable=SC2086
      so_walls+="$(native_wall "$p" "${mbc%.mbc}.so" $meld_args)"$'\n' || { failed=1; break; }
      # shellcheck disable=SC2086
      jit_walls+="$(native_wall "$p" "$mbc" --jit $meld_args)"$'\n' || { failed=1; break; }
    fi
    [ -n "$d" ] && rates+="$(awk -v d="$d" -v w="$w" 'BEGIN{if (w > 0) printf "%.0f", d / w}')"$'\n'
    rss="$(statval "peak RSS MB" < "$log")"; [ -n "$rss" ] && rsss+="$rss"$'\n'
  done
  if [ "$failed" = 1 ]; then status=1; continue; fi
  wall="$(printf "%s" "$walls" | median)"
  rate="$(printf "%s" "$rates" | grep . | median || true)"
  rssm="$(printf "%s" "$rsss" | grep . | median || true)"
  so_wall="" jit_wall=""
  if [ "$native" = 1 ]; then
    so_wall="$(printf "%s" "$so_walls" | median)"
    jit_wall="$(printf "%s" "$jit_walls" | median)"
  fi
  if [ "$json" = 1 ]; then
    printf '{"program":"%s","size":"%s","generator_args":"%s","runs":%s,"wall_s":%s,"facts_derived":%s,"facts_consumed":%s,"facts_sent":%s,"rules_fired":%s,"facts_per_s":%s,"peak_rss_mb":%s,"so_wall_s":%s,"jit_wall_s":%s,"meld":"%s","meld_args":"%s"}\n' \
      "$p" "$size" "$a" "$runs" "$wall" "$(num_or_null "$derived")" "$(num_or_null "$consumed")" \
      "$(num_or_null "$sent")" "$(num_or_null "$fired")" "$(num_or_null "$rate")" "$(num_or_null "$rssm")" \
      "$(num_or_null "$so_wall")" "$(num_or_null "$jit_wall")" "$meld" "$meld_args"
  else
    printf "%-19s %-34s %4s %9.3f %13s %13s %10s %9s" "$p" "$size" "$runs" "$wall" "${derived:-?}" "${fired:-?}" \
      "$([ -n "$rate" ] && awk -v r="$rate" 'BEGIN{printf "%.2f", r / 1e6}' || echo '?')" "${rssm:-?}"
    if [ "$native" = 1 ]; then
      printf " %8.3f %8.3f %7.2f %7.2f" "$so_wall" "$jit_wall" "$(awk -v a="$wall" -v b="$so_wall" 'BEGIN{print a / b}')" \
        "$(awk -v a="$wall" -v b="$jit_wall" 'BEGIN{print a / b}')"
    fi
    printf "\n"
  fi
done
exit "$status"
