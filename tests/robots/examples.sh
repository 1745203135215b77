#!/bin/sh
# Golden tests of the Meld robot examples (examples/meld/*.meld on examples/worlds/meld-*.xml):
# `vsim WORLD --program PROG --dump` on the world's own schedule; the summary (without the lines
# that depend on the machine: world and program paths, wall time, events/s) and the final facts of
# every block are compared with tests/robots/expected/NAME.out. A second run must print the same.
# Usage: examples.sh NAME (environment: VSIM, SRC, WORK). UPDATE_GOLDEN=1 rewrites the golden file.
set -u
name="$1"
rm -rf "$WORK" && mkdir -p "$WORK"
run() {
  "$VSIM" "$SRC/examples/worlds/meld-$name.xml" --program "$SRC/examples/meld/$name.meld" --dump --no-progress \
    > "$WORK/raw$1" 2> "$WORK/err$1" || { echo "FAIL: vsim exited with $?"; cat "$WORK/err$1"; exit 1; }
  grep -v -e '^  world ' -e '^  block code ' -e '^  wall time ' -e '^  events/s ' "$WORK/raw$1" > "$WORK/out$1"
}
run 1
run 2
cmp -s "$WORK/out1" "$WORK/out2" || { echo "FAIL: two runs differ"; diff "$WORK/out1" "$WORK/out2"; exit 1; }
golden="$SRC/tests/robots/expected/$name.out"
if [ "${UPDATE_GOLDEN:-}" = 1 ]; then cp "$WORK/out1" "$golden"; echo "updated $golden"; exit 0; fi
diff -u "$golden" "$WORK/out1" || { echo "FAIL: differs from $golden"; exit 1; }
