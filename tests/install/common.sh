# Shared by the install tests (sourced): failing with a message, and the checks each of them makes
# of an installed tree.

fail() { echo "FAIL: $*"; exit 1; }

# expect_files ROOT FILE...: each FILE exists under ROOT.
expect_files() {
  root=$1
  shift
  for f in "$@"; do
    [ -e "$root/$f" ] || fail "/$f is not installed under $root"
  done
}

# run_or_fail OUT WHAT COMMAND...: runs COMMAND with its output in OUT; on failure shows OUT.
run_or_fail() {
  out=$1 what=$2
  shift 2
  "$@" >"$out" 2>&1 || { cat "$out"; fail "$what"; }
}

# check_demo PREFIX OUT: the installed vsim runs the demo world with the installed BlockCode, found
# by name next to the program (PREFIX/lib/meld/blockcodes).
check_demo() {
  run_or_fail "$2" "the installed vsim did not run the demo" \
    "$1/bin/vsim" "$1/share/meld/examples/worlds/color-flood.xml" --no-progress
  grep -q "block code      color-flood ($1/lib/meld/blockcodes/color_flood.so)" "$2" ||
    { cat "$2"; fail "the demo did not run the installed BlockCode"; }
}

# fingerprint OUT: the run fingerprint of a vsim summary.
fingerprint() { awk '/fingerprint/ {print $2}' "$1"; }
