#!/bin/sh
# Golden tests of the Meld robot examples (examples/meld/*.meld on examples/worlds/meld-*.xml):
# `vsim WORLD --program PROG --dump` on the world's own schedule; the summary (without the lines
# that depend on the machine: world and program paths, wall time, events/s) and the final facts of
# every block are compared with tests/robots/expected/NAME.out. A second run must print the same.
# Usage: examples.sh NAME (environment: VSIM, SRC, WORK). UPDATE_GOLDEN=1 rewrites the golden file.
# MODE=jit runs the program as native code (vsim --jit); MODE=so with MELDC compiles it with
# `meldc --robots --emit=native` and runs the shared object. Both against the same golden.
set -u
name="$1"
rm -rf "$WORK" && mkdir -p "$WORK"
program="$SRC/examples/meld/$name.meld"
flags=""
case "${MODE:-}" in
  jit) flags="--jit" ;;
  so)
    "$MELDC" --robots --emit=native "$program" -o "$WORK/$name.so" || { echo "FAIL: meldc --emit=native"; exit 1; }
    program="$WORK/$name.so"
    ;;
esac
run() {
  "$VSIM" "$SRC/examples/worlds/meld-$name.xml" --program "$program" $flags --dump --no-progress \
    > "$WORK/raw$1" 2> "$WORK/err$1" || { echo "FAIL: vsim exited with $?"; cat "$WORK/err$1"; exit 1; }
  grep -v -e '^  world ' -e '^  block code ' -e '^  wall time ' -e '^  events/s ' "$WORK/raw$1" > "$WORK/out$1"
}
run 1
run 2
cmp -s "$WORK/out1" "$WORK/out2" || { echo "FAIL: two runs differ"; diff "$WORK/out1" "$WORK/out2"; exit 1; }
golden="$SRC/tests/robots/expected/$name.out"
if [ "${UPDATE_GOLDEN:-}" = 1 ]; then cp "$WORK/out1" "$golden"; echo "updated $golden"; exit 0; fi
diff -u "$golden" "$WORK/out1" || { echo "FAIL: differs from $golden"; exit 1; }
