#!/bin/sh
# The vsim command-line tests, one function per case; tests/cli/CMakeLists.txt runs
# `cases.sh NAME` for each (CTest test cli.NAME). Keeping them in one script keeps them readable:
# arguments with ';' (trace filters) would otherwise have to survive CMake list splitting.
#
# Environment: VSIM (the binary), BLOCKCODES (folder of the example .so files), NO_ENTRY_SO and
# BAD_ABI_SO (broken block programs), SRC (repository root), WORK (scratch folder for this case),
# CMAKE (the cmake that configured the build; used as a JSON parser).
# UPDATE_GOLDEN=1 rewrites the golden files in tests/cli/expected/ instead of comparing.
set -u
EXPECTED="$SRC/tests/cli/expected"
WORLDS="$SRC/examples/worlds"
TWORLDS="$SRC/tests/cli/worlds"
FLOOD="$BLOCKCODES/color_flood.so"
TAPS="$BLOCKCODES/tap_cycle.so"
rm -rf "$WORK"
mkdir -p "$WORK"
OUT="$WORK/stdout"
ERR="$WORK/stderr"
: >"$OUT"
: >"$ERR"
BIN=$VSIM
# fail, run RC ARGS... and has FILE TEXT
. "$SRC/tests/common/cli_helpers.sh"

# stable FILE: the output without the lines that change between runs or machines.
stable() { grep -v -E '^  (world|block code|wall time|events/s) ' "$1"; }

# golden NAME FILE: stable(FILE) must equal tests/cli/expected/NAME.
golden() {
  if [ "${UPDATE_GOLDEN:-0}" = 1 ]; then
    stable "$2" >"$EXPECTED/$1"
    echo "updated $EXPECTED/$1"
    return
  fi
  stable "$2" | diff -u "$EXPECTED/$1" - >"$WORK/diff" || {
    cat "$WORK/diff" >&2
    fail "output differs from tests/cli/expected/$1 (UPDATE_GOLDEN=1 ctest -R cli rewrites it)"
  }
}

fingerprint() { sed -n 's/^  fingerprint *//p' "$1"; }
histogram() { sed -n '/^  colors /,/^  final blocks/p' "$1" | grep -v 'final blocks'; }

# --- command line --------------------------------------------------------------------------

case_help() {
  run 0 --help
  has "$OUT" "usage: vsim WORLD.xml"
  has "$OUT" "exit codes:"
  has "$OUT" "--until"
}

case_version() {
  run 0 --version
  has "$OUT" "vsim "
}

case_unknown_option() {
  run 2 "$WORLDS/color-flood.xml" --frobnicate
  has "$ERR" "unknown option '--frobnicate'"
}

case_no_world() {
  run 2 --code "$FLOOD"
  has "$ERR" "no world file"
}

case_bad_until() {
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --until soon
  has "$ERR" "--until wants a duration"
}

case_bad_trace_filter() {
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --trace 'blocks=0;kinds=bogus'
  has "$ERR" "unknown kind 'bogus'"
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --trace 'blocks=9-2'
  has "$ERR" "range '9-2' is empty"
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --trace 'from=2s;to=1s'
  has "$ERR" "'from' is after 'to'"
}

case_bad_tap() {
  run 2 "$WORLDS/tap-cycle.xml" --code "$TAPS" --tap 99@1s
  has "$ERR" "no block 99"
  run 2 "$WORLDS/tap-cycle.xml" --code "$TAPS" --tap 1
  has "$ERR" "--tap wants BLOCK@TIME"
}

case_unknown_target_option() {
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --target catoms9d
  has "$ERR" "unknown target 'catoms9d'"
}

case_no_code() {
  run 2 "$TWORLDS/no-code.xml"
  has "$ERR" "no block code"
}

# --- inputs --------------------------------------------------------------------------------

case_missing_world() {
  run 3 "$WORK/does-not-exist.xml" --code "$FLOOD"
  has "$ERR" "does-not-exist.xml"
}

case_broken_world() {
  run 3 "$TWORLDS/broken.xml" --code "$FLOOD"
  has "$ERR" "broken.xml:5:"
  has "$ERR" "error:"
}

case_unknown_target_world() {
  run 3 "$TWORLDS/bad-target.xml" --code "$FLOOD"
  has "$ERR" "bad-target.xml:3:25: error: unknown target 'catoms9d'"
}

case_code_missing() {
  run 3 "$WORLDS/color-flood.xml" --code "$WORK/nothing.so"
  has "$ERR" "nothing.so"
}

case_code_not_elf() {
  run 3 "$WORLDS/color-flood.xml" --code "$WORLDS/color-flood.xml"
  has "$ERR" "is not a shared object"
}

case_code_no_entry() {
  run 3 "$WORLDS/color-flood.xml" --code "$NO_ENTRY_SO"
  has "$ERR" "does not export \`vs_blockcode_entry\`"
}

case_code_bad_abi() {
  run 3 "$WORLDS/color-flood.xml" --code "$BAD_ABI_SO"
  has "$ERR" "block ABI version 999"
}

# --- runs ----------------------------------------------------------------------------------

case_flood_small() {
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD"
  golden flood-small.txt "$OUT"
}

case_flood_demo() {
  run 0 "$WORLDS/color-flood.xml" --code "$FLOOD" --stats
  golden flood-demo.txt "$OUT"
}

case_flood_smartblocks() {
  run 0 "$WORLDS/smartblocks-line.xml" --code "$FLOOD"
  golden flood-smartblocks.txt "$OUT"
}

case_tap_cycle() {
  run 0 "$WORLDS/tap-cycle.xml" --code "$TAPS" --tap 0@5s --tap 1@6s,1@7s
  golden tap-cycle.txt "$OUT"
}

case_until() {
  run 0 "$WORLDS/color-flood.xml" --code "$FLOOD" --until 500ms
  has "$OUT" "--until reached, 1 event pending"
  has "$OUT" "0.500000000 s"
}

case_until_past_the_end() {
  # The queue empties at 2.0 s; the world was simulated (quiet) up to --until.
  run 0 "$WORLDS/meld-gradient-tap.xml" --until 100s
  has "$OUT" "queue empty"
  has "$OUT" "100.000000000 s"
}

case_world_program() {
  # program= in the world names the Meld program: no --program needed.
  run 0 "$WORLDS/meld-rainbow.xml"
  has "$OUT" "meld-vm"
}

case_why() {
  # Why a fact exists on a block (issue 11, point 6): the gradient's distance 2 on block 10 came
  # from block 17 as a message, which got distance 1 from the tapped block 24; the tree goes
  # down to the tap and the neighbor facts the blocks sensed, each rule step at its FILE:LINE
  # (the world is named relative to the repository: stable paths).
  cd "$SRC" || fail "no repository"
  run 0 examples/worlds/meld-gradient-tap.xml --why 'dist(2)@10' --quiet
  golden why-gradient.txt "$OUT"
  run 0 examples/worlds/meld-gradient-tap.xml --why '!dist(@10, 2)' --quiet
  golden why-gradient.txt "$OUT"
  run 1 examples/worlds/meld-gradient-tap.xml --why 'dist(5)@10' --quiet
  has "$ERR" "the run did not derive dist(5)@10"
  run 2 examples/worlds/meld-gradient-tap.xml --why 'nosuch(1)@3'
  has "$ERR" "--why: the program has no predicate 'nosuch'"
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --why 'dist(1)@3'
  has "$ERR" "--why, --time-per-rule, --jit and -I go with a Meld program"
}

# --- the multicore target (a Meld program on a simulated chip) -----------------------------

case_multicore() {
  # The conformance suite runs on a 4-core chip (conformance.chip4.*); here: the report, a sweep,
  # program arguments after --, the options of the chip, the profile, and the dump (the same on
  # any chip).
  P="$SRC/tests/conformance/args.meld"
  run 0 --target multicore --program "$P" --cores 1,2,4 -- 7 hello
  has "$OUT" "multicore: mesh, 50 ns per hop, stealing on"
  has "$OUT" "  cores    predicted ms  speedup  efficiency"
  has "$OUT" "per core (4 cores):"
  [ "$(awk '/predicted ms/ { on = 1; next } /^per core/ { on = 0 } on' "$OUT" | awk '{ print $1 }' | tr '\n' ' ')" = "1 2 4 " ] ||
    fail "not one sweep line per core count"
  run 0 --target multicore --program "$P" --cores 3 --topology ring --hop-latency 10 --no-steal \
    --costs rule=5,send=1 --dump --quiet --profile "$WORK/chip.json" -- 7 hello
  (cd "$SRC/tests/conformance" && "$VSIM" --target multicore --program args.meld --dump --quiet -- 7 hello) >"$WORK/dump" ||
    fail "the dump run failed"
  cmp -s "$OUT" "$WORK/dump" || fail "the dump depends on the chip's topology or costs"
  diff -u "$SRC/tests/conformance/args.expected" "$OUT" >&2 || fail "the chip's dump differs from the golden"
  has "$WORK/chip.json" '"name":"vsim multicore 3 cores"'
  has "$WORK/chip.json" '"name":"core 2"'
}

case_native() {
  # --jit and --program FILE.so (meldc --robots --emit=native): the bytecode's run, fingerprint
  # included; the errors of native programs.
  W="$WORLDS/meld-token-walk.xml"
  run 0 "$W" --no-progress
  fingerprint "$OUT" >"$WORK/bytecode"
  run 0 "$W" --no-progress --jit
  fingerprint "$OUT" | cmp -s - "$WORK/bytecode" || fail "--jit changed the fingerprint"
  "$MELDC" --robots --emit=native "$SRC/examples/meld/token-walk.meld" -o "$WORK/walk.so" || fail "meldc"
  run 0 "$W" --program "$WORK/walk.so" --no-progress
  fingerprint "$OUT" | cmp -s - "$WORK/bytecode" || fail "walk.so changed the fingerprint"
  run 3 "$W" --program "$WORK/walk.so" --jit
  has "$ERR" "native code already"
  run 3 "$W" --program "$FLOOD"
  has "$ERR" "not a native Meld program"
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --jit
  has "$ERR" "--jit and -I go with a Meld program"
  run 0 --target multicore --program "$WORK/walk.so" --cores 2 --quiet
  run 0 --target multicore --program "$SRC/tests/conformance/args.meld" --cores 2 --jit --quiet -- 7 hello
}

case_multicore_errors() {
  P="$SRC/tests/conformance/args.meld"
  run 2 --target multicore
  has "$ERR" "--target multicore needs --program PROG.meld|PROG.mbc|PROG.so"
  run 2 "$WORLDS/color-flood.xml" --target multicore --program "$P"
  has "$ERR" "no world file (got"
  run 2 --target multicore --program "$P" --cores 0
  has "$ERR" "--cores wants core counts from 1 to 1024"
  run 2 --target multicore --program "$P" --cores 2,x
  has "$ERR" "got 'x'"
  run 2 --target multicore --program "$P" --topology torus
  has "$ERR" "--topology is mesh, ring or full, got 'torus'"
  run 2 --target multicore --program "$P" --costs rule
  has "$ERR" "--costs wants NAME=NS pairs"
  run 2 --target multicore --program "$P" --costs speed=3
  has "$ERR" "--costs: unknown cost 'speed'"
  run 2 --target multicore --program "$P" --hop-latency -5
  has "$ERR" "--hop-latency wants a non-negative number of nanoseconds"
  run 2 --target multicore --program "$P" --tap 1@1s
  has "$ERR" "--tap is for worlds, not for --target multicore"
  run 2 "$WORLDS/color-flood.xml" --code "$FLOOD" --cores 4
  has "$ERR" "are for --target multicore"
  run 3 --target multicore --program "$WORK/nosuch.meld"
  has "$ERR" "nosuch.meld"
  printf 'type route e(node, node).\nthis is not meld\n' >"$WORK/bad.meld"
  run 3 --target multicore --program "$WORK/bad.meld"
  has "$ERR" "bad.meld:2:"
  run 1 --target multicore --program "$P" --profile "$WORK/no/such/dir/p.json"
  has "$ERR" "--profile: cannot write"
  # A run-time error on the chip: integer division by zero.
  printf 'type linear p(node, int).\np(@0, 1).\np(A, X) -o p(A, 1 / (X - 1)).\n' >"$WORK/div.meld"
  run 1 --target multicore --program "$WORK/div.meld" --cores 2
  has "$ERR" "Meld program failed on the 2-core chip"
}

case_visiblesim_world() {
  # VisibleSim's forms (vs root, gridsize, bitmap rows, blockBox, #RRGGBB) with a Meld program
  # named by the world: 13 blocks; the 12 connected ones elect id 11 (blue, 11 % 6 = 5), block 12
  # alone at (0,3,0) leads itself (white).
  run 0 "$TWORLDS/visiblesim-bitmap.xml" --dump
  has "$OUT" "blocks          13"
  has "$OUT" "#0000ff blue               11"
  has "$OUT" "#ffffff white               2"
}

case_world_without_blocks() {
  run 3 "$TWORLDS/no-blocks.xml" --code "$FLOOD"
  has "$ERR" "no-blocks.xml:2:1: error: the world has no block (no <block>, <blocksBox>, <blockBox>, <blocksLine> or <csg> in a <blockList>)"
}

case_csg_world() {
  # VisibleSim's <csg> solid: the dome example (worked out in its comment) with its own program.
  run 0 "$WORLDS/blinky-csg-dome.xml" --dump
  has "$OUT" "blocks          315"
}

case_csg_errors() {
  run 3 "$TWORLDS/csg-outside.xml" --code "$FLOOD"
  has "$ERR" "csg-outside.xml:4:5: error: the <csg> solid holds no cell of the grid, and the world has no other block"
  run 3 "$TWORLDS/csg-syntax.xml" --code "$FLOOD"
  has "$ERR" "csg-syntax.xml:4:53: error: <csg content>: unknown variable 'radius'"
}

case_same_fingerprint() {
  # Twice the same, and the same with every future-event set (and the default, the ladder queue:
  # simcore::kDefaultFes): the order of events is total.
  for fes in heap heap calendar ladder default; do
    if [ $fes = default ]; then run 0 "$WORLDS/color-flood.xml" --code "$FLOOD"; else
      run 0 "$WORLDS/color-flood.xml" --code "$FLOOD" --fes $fes; fi
    fingerprint "$OUT" >>"$WORK/fingerprints"
  done
  run 0 "$WORLDS/color-flood.xml" --code "$FLOOD" --json -
  has "$OUT" '"fes":"ladder"'
  [ "$(sort -u "$WORK/fingerprints" | wc -l)" -eq 1 ] || fail "fingerprints differ: $(cat "$WORK/fingerprints")"
  [ -n "$(head -n 1 "$WORK/fingerprints")" ] || fail "no fingerprint line"
}

case_trace_text() {
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD" --trace 'blocks=0-1;kinds=start,send,message,color,trace;to=10ms' \
    --trace-file "$WORK/trace.txt"
  golden trace-text.txt "$WORK/trace.txt"
}

case_trace_json() {
  run 0 "$WORLDS/tap-cycle.xml" --code "$TAPS" --trace 'kinds=tap,color,trace' --trace-format json \
    --trace-file "$WORK/trace.jsonl"
  golden trace-json.jsonl "$WORK/trace.jsonl"
}

case_json_report() {
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD" --json "$WORK/report.json"
  # CMake's JSON parser checks that the file is valid JSON and reads fields back.
  "${CMAKE:-cmake}" -DFILE="$WORK/report.json" -DKEYS="fingerprint;blocks;end;statistics.messages_sent" \
    -P "$SRC/tests/cli/json_get.cmake" >"$WORK/fields" 2>&1 || { cat "$WORK/fields" >&2; fail "bad JSON report"; }
  has "$WORK/fields" "fingerprint=$(fingerprint "$OUT")"
  has "$WORK/fields" "blocks=18"
  has "$WORK/fields" "end=queue-empty"
}

case_export_reload() {
  # The exported world keeps the final colors: a run that changes no color (tap_cycle without
  # taps) on it ends with the same histogram as the run that produced it.
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD" --export "$WORK/final.xml"
  histogram "$OUT" >"$WORK/histogram-before"
  run 0 "$WORK/final.xml" --code "$TAPS"
  histogram "$OUT" >"$WORK/histogram-after"
  has "$OUT" "blocks          18"
  diff -u "$WORK/histogram-before" "$WORK/histogram-after" >&2 || fail "the exported world lost the final colors"
  # It names the code that ran (absolute path) and the seed: it runs again without --code.
  run 0 "$WORK/final.xml"
  has "$OUT" "color-flood"
  has "$WORK/final.xml" 'seed="1"'
}

case_export_gltf() {
  # The final configuration as glTF 2.0: a node per block, a material per colour; cubes for
  # Smart Blocks, spheres for Catoms 3D. check_glb.py re-reads the file as a reader would.
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD" --export-gltf "$WORK/final.glb"
  colors=$(sed -n 's/^  colors *\([0-9]*\) distinct.*/\1/p' "$OUT")
  python3 "$SRC/tests/cli/check_glb.py" "$WORK/final.glb" >"$WORK/glb" || fail "final.glb is not valid glTF"
  has "$WORK/glb" "nodes 18 materials $colors meshes $colors shape 24"
  # Each block in its colour: the same histogram as vsim's summary.
  sed -n 's/^    \(#[0-9a-f]*\) *[a-z]* *\([0-9]*\)$/\1 \2/p' "$OUT" | sort -k2,2nr -k1,1 >"$WORK/vsim-colors"
  tail -n +2 "$WORK/glb" >"$WORK/glb-colors"
  diff -u "$WORK/vsim-colors" "$WORK/glb-colors" >&2 || fail "the glTF blocks are not in their colours"
  run 0 "$WORLDS/catoms3d-box.xml" --code "$FLOOD" --export-gltf "$WORK/catoms.glb"
  python3 "$SRC/tests/cli/check_glb.py" "$WORK/catoms.glb" >"$WORK/glb3" || fail "catoms.glb is not valid glTF"
  has "$WORK/glb3" "shape 153"
  run 2 "$TWORLDS/flood-small.xml" --code "$FLOOD" --export-gltf -
  has "$ERR" "--export-gltf needs a file name"
  run 1 "$TWORLDS/flood-small.xml" --code "$FLOOD" --export-gltf /no/such/dir/x.glb
  has "$ERR" "cannot write '/no/such/dir/x.glb'"
}

case_stability() {
  # The reality checker on worlds worked out by hand (tests/simcore/test_stability.cpp has the
  # figures): a world alone is checked as loaded, exit status 4 when it does not hold.
  run 4 "$WORLDS/stability-overhang.xml" --check-stability
  has "$OUT" "stability: unstable (1 link overloaded; largest link force 4.41 N of 2.50 N)"
  has "$OUT" "  link #4 right -> #5: must carry 4.41 N, holds 2.50 N (3 blocks' weight on it)"
  run 4 "$WORLDS/stability-tipping.xml" --check-stability
  has "$OUT" "it tips about the axis (20.0, -20.0) - (20.0, 20.0) mm of floor block #0"
  run 0 "$WORLDS/catoms3d-pyramid.xml" --check-stability --until 0
  has "$OUT" "stability: stable (1 structure of 14 blocks"
  has "$OUT" "motions checked 0, 0 would not hold"
  # During a run: the second roll would tip the catoms; reported (the run goes on and ends
  # unstable), or refused (the catom stays, the world stands).
  run 4 "$TWORLDS/catoms2d-tip.xml" --check-stability --no-progress
  has "$ERR" "vsim: warning: at 1.000000000 s block #4 moving to (2,0,1): stability: unstable (1 structure tips over"
  has "$OUT" "    #4   (2,0,1)"
  has "$OUT" "it tips about the corner (10.0, 0.0) mm of floor block #1"
  has "$OUT" "motions checked 2, 1 would not hold"
  run 0 "$TWORLDS/catoms2d-tip.xml" --refuse-unstable --no-progress
  has "$ERR" "vsim: refused: at 1.000000000 s block #4 moving to (2,0,1)"
  has "$OUT" "    #4   (2,0,2)"
  has "$OUT" "stability: stable"
  has "$OUT" "motions checked 2, 1 refused as unstable"
  # A world that does not hold as loaded cannot be run with --refuse-unstable.
  run 4 "$WORLDS/stability-tipping.xml" --refuse-unstable --code "$FLOOD"
  has "$ERR" "vsim: error: --refuse-unstable: the world does not hold as loaded"
  run 2 "$WORLDS/smartblocks-line.xml" --check-stability
  has "$ERR" "--check-stability: smartblocks blocks lie on a surface, not under gravity"
}

case_polling_wave() {
  # The same wave written with callbacks and as a loop that waits (coroutines): the same run
  # (fingerprint) and the same trace of messages, sends and colours.
  for style in events polling; do
    run 0 "$WORLDS/color-flood.xml" --code "$BLOCKCODES/wave_$style.so" --no-progress \
      --trace kinds=message,send,color --trace-file "$WORK/trace-$style"
    fingerprint "$OUT" >"$WORK/fp-$style"
    has "$OUT" "  block code      wave-$style"
  done
  [ "$(wc -l <"$WORK/trace-polling")" -gt 500 ] || fail "the wave trace is too short"
  cmp -s "$WORK/fp-events" "$WORK/fp-polling" || fail "the two styles ran differently"
  diff -u "$WORK/trace-events" "$WORK/trace-polling" >&2 || fail "the two styles' traces differ"
}

case_conveyor() {
  # The VisibleSim paper's air-jet experiment (Fig. 11): the part follows the broken line within the
  # goals (mean distance <= 15 mm between 2 s and 24 s, final position within 20 mm of (400, 75)),
  # the same run twice, and halving the physics step moves the trajectory by less than 1 mm.
  W="$WORLDS/smartblocks-conveyor.xml"
  run 0 "$W" --code "$BLOCKCODES/conveyor.so" --mobiles-csv "$WORK/traj.csv" --no-progress
  fingerprint "$OUT" >"$WORK/fp1"
  [ "$(head -n 1 "$WORK/traj.csv")" = "t,mobile,x,y,angle" ] || fail "no CSV header"
  [ "$(wc -l <"$WORK/traj.csv")" -gt 20000 ] || fail "fewer physics steps than 20 s of 1 ms"
  sh "$SRC/examples/physics/conveyor-figures.sh" "$WORK/traj.csv" >"$WORK/figures" || fail "conveyor-figures.sh failed"
  cat "$WORK/figures"
  awk '/^mean distance/ { m = $(NF - 1) } /^final position/ { d = $(NF - 4) }
       END { exit !(m != "" && m <= 15 && d != "" && d <= 20) }' "$WORK/figures" || fail "the part missed the goals"
  run 0 "$W" --code "$BLOCKCODES/conveyor.so" --no-progress
  fingerprint "$OUT" | cmp -s - "$WORK/fp1" || fail "two runs differ"
  run 0 "$W" --code "$BLOCKCODES/conveyor.so" --mobiles-csv "$WORK/half.csv" --physics-step 0.5ms --no-progress
  sh "$SRC/examples/physics/conveyor-figures.sh" "$WORK/traj.csv" "$WORK/half.csv" >"$WORK/halved" || fail "figures of two runs"
  cat "$WORK/halved"
  awk '/^largest distance between/ { a = $(NF - 4) } END { exit !(a != "" && a < 1) }' "$WORK/halved" ||
    fail "halving the step moved the trajectory by 1 mm or more"
  # The same controller in Meld, in every execution mode: bytecode, native code in memory (--jit)
  # and a native shared object (meldc --robots --emit=native): one run, within the goals.
  M="$WORLDS/meld-conveyor.xml"
  run 0 "$M" --mobiles-csv "$WORK/meld.csv" --no-progress
  fingerprint "$OUT" >"$WORK/fp-meld"
  sh "$SRC/examples/physics/conveyor-figures.sh" "$WORK/meld.csv" >"$WORK/meld-figures" || fail "figures of the Meld run"
  cat "$WORK/meld-figures"
  awk '/^mean distance/ { m = $(NF - 1) } /^final position/ { d = $(NF - 4) }
       END { exit !(m != "" && m <= 15 && d != "" && d <= 20) }' "$WORK/meld-figures" || fail "the Meld controller missed the goals"
  run 0 "$M" --jit --mobiles-csv "$WORK/jit.csv" --no-progress
  fingerprint "$OUT" | cmp -s - "$WORK/fp-meld" || fail "--jit ran differently"
  cmp -s "$WORK/meld.csv" "$WORK/jit.csv" || fail "--jit moved the part differently"
  "$MELDC" --robots --emit=native "$SRC/examples/meld/conveyor.meld" -o "$WORK/conveyor.so" || fail "meldc --emit=native"
  run 0 "$M" --program "$WORK/conveyor.so" --no-progress
  fingerprint "$OUT" | cmp -s - "$WORK/fp-meld" || fail "the native .so ran differently"
  # --export writes the part where it ended; the exported world loads with it there.
  run 0 "$W" --code "$BLOCKCODES/conveyor.so" --no-progress --export "$WORK/final.xml"
  has "$WORK/final.xml" '<mobile position="400'
  has "$WORK/final.xml" 'size="50,50" mass="0.02"'
  run 0 "$WORK/final.xml" --code "$BLOCKCODES/conveyor.so" --until 100ms --mobiles-csv "$WORK/again.csv" --no-progress
  awk -F, 'NR == 2 { exit !($3 > 399 && $3 < 401 && $4 > 74 && $4 < 76) }' "$WORK/again.csv" ||
    fail "the exported world does not put the part where it ended"
  # The final configuration for renderers: 400 blocks and the part (an orange slab).
  run 0 "$W" --code "$BLOCKCODES/conveyor.so" --no-progress --export-gltf "$WORK/final.glb"
  python3 "$SRC/tests/cli/check_glb.py" "$WORK/final.glb" >"$WORK/glb" || fail "final.glb is not valid glTF"
  has "$WORK/glb" "nodes 401 materials 2"
  has "$WORK/glb" "#e08020 1"
  run 2 "$TWORLDS/flood-small.xml" --code "$FLOOD" --mobiles-csv "$WORK/none.csv"
  has "$ERR" "--mobiles-csv: $TWORLDS/flood-small.xml has no mobiles (<mobileList>)"
  run 2 "$W" --physics-step 0
  has "$ERR" "--physics-step must be longer than 0"
}

case_code_search() {
  # A BlockCode named by file name alone is searched for: next to the world, on VSIM_CODE_PATH,
  # then in the build (or installation) of the vsim that runs.
  run 0 "$WORLDS/color-flood.xml" --no-progress
  has "$OUT" "blockcodes/color_flood.so)"
  run 0 "$WORLDS/tap-cycle.xml" --code tap_cycle.so --no-progress
  has "$OUT" "blockcodes/tap_cycle.so)"
  mkdir -p "$WORK/mine"
  cp "$TAPS" "$WORK/mine/my_taps.so"
  sed 's|code="tap_cycle.so"|code="my_taps.so"|' "$WORLDS/tap-cycle.xml" >"$WORK/taps.xml"
  run 3 "$WORK/taps.xml"
  has "$ERR" "block code 'my_taps.so' not found; looked in $WORK,"
  has "$ERR" "(set VSIM_CODE_PATH to the folder that holds it)"
  export VSIM_CODE_PATH="/nonexistent:$WORK/mine"
  run 0 "$WORK/taps.xml" --no-progress
  unset VSIM_CODE_PATH
  has "$OUT" "$WORK/mine/my_taps.so)"
}

case_link_options() {
  # Slower links stretch the flood in simulated time; a bad rate is a usage error.
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD"
  sed -n "s/^  simulated time *//p" "$OUT" | head -n 1 >"$WORK/fast"
  fingerprint "$OUT" >"$WORK/fast-fp"
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD" --link-rate 9600 --link-latency 2ms --link-jitter 1ms
  sed -n "s/^  simulated time *//p" "$OUT" | head -n 1 >"$WORK/slow"
  fingerprint "$OUT" >"$WORK/slow-fp"
  cmp -s "$WORK/fast-fp" "$WORK/slow-fp" && fail "link options did not change the run"
  awk -v f="$(cut -d' ' -f1 "$WORK/fast")" -v s="$(cut -d' ' -f1 "$WORK/slow")" 'BEGIN { exit !(s > f) }' ||
    fail "a slower link did not make the flood take longer ($(cat "$WORK/fast") vs $(cat "$WORK/slow"))"
  run 2 "$TWORLDS/flood-small.xml" --code "$FLOOD" --link-rate 0
  has "$ERR" "--link-rate wants a positive number"
  run 2 "$TWORLDS/flood-small.xml" --code "$FLOOD" --motion-time soon
  has "$ERR" "--motion-time wants a duration"
}

case_quiet() {
  run 0 "$TWORLDS/flood-small.xml" --code "$FLOOD" --quiet
  [ ! -s "$OUT" ] || fail "--quiet printed a summary"
}

name=$(echo "${1:?usage: cases.sh CASE}" | tr - _)
"case_$name"
echo "ok: $1"
