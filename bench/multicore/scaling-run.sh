#!/usr/bin/env bash
# The run side of bench/multicore/scaling-kit.sh (copied into the kit as run.sh): on the machine
# being measured, unpacks the kit's programs and runs bench/multicore/scaling.py over them with
# both VMs, after the machine's description and a same-work check (n-queens' and 8queens-12's
# dumps at one and at the most threads).
#   bash KIT/run.sh [THREADS [ROUNDS [BUDGET_S]]]
# THREADS: comma-separated thread counts (default 1,2,4,... up to nproc); ROUNDS: default 3;
# BUDGET_S: no round starts that would end past it (default 480). The log, lscpu and
# scaling.json go to $OUT, or to the kit's folder where OUT is unset.
set -uo pipefail
kit="$(cd "$(dirname "$0")" && pwd)"
scaling="$kit/../../bench/multicore/scaling.py"  # the kit lives in build/ of the repository
out="${OUT:-$kit}"
cores=$(nproc)
threads="${1:-}"
if [ -z "$threads" ]; then
  threads=1
  for ((t = 2; t <= cores; t *= 2)); do threads="$threads,$t"; done
fi
rounds="${2:-3}" budget="${3:-480}"
top="${threads##*,}"
exec > >(tee "$out/log.txt") 2>&1
echo "== machine: $cores cores, $(uname -r), $(date -u)"
lscpu > "$out/lscpu.txt" 2>&1 || true
grep -E "Model name|^CPU\(s\)|Thread|Core|Socket|NUMA node\(s\)|L3" "$out/lscpu.txt"
work="$(mktemp -d)"
python3 -c "import sys, tarfile; tarfile.open(sys.argv[1]).extractall(sys.argv[2])" \
  "$kit/programs.tar.xz" "$work" || { echo "run.sh: cannot unpack the programs" >&2; exit 1; }
"$kit/meld" --version || { echo "run.sh: the kit's meld does not run here" >&2; exit 1; }
echo "== same work at 1 and $top threads (md5 of the dumps)"
for p in n-queens 8queens-12; do
  [ -f "$work/programs/$p.mbc" ] || continue
  for t in 1 "$top"; do
    echo "$p -j $t $("$kit/meld" "$work/programs/$p.mbc" -j "$t" --dump | md5sum)"
  done
done
specs=()
while read -r spec; do specs+=("$work/$spec"); done < "$kit/programs.txt"
rss=()
[ -x "$kit/gnu-time" ] && rss=(--gnu-time "$kit/gnu-time")
echo "== scaling: threads $threads, $rounds rounds, budget $budget s"
PYTHONUNBUFFERED=1 python3 "$scaling" --meld "$kit/meld" --meld-ref "$kit/meld-ref" "${rss[@]}" \
  --threads "$threads" --runs "$rounds" --budget "$budget" --timeout 120 \
  --unscheduled new-heat-transfer-80 --json "$out/scaling.json" "${specs[@]}"
status=$?
rm -rf "$work"
echo "== done $(date -u)"
exit $status
