# Helpers of the command-line test scripts (tests/meldc/cli.sh, tests/meld/cli.sh), sourced after
# the caller has set BIN (the program under test), OUT and ERR (where a run's output goes).

fail() {
  echo "FAIL: $*"
  echo "--- stdout"; cat "$OUT"
  echo "--- stderr"; cat "$ERR"
  exit 1
}

# run RC ARGS...: runs the program with no standard input, checks its exit code.
run() {
  want=$1
  shift
  "$BIN" "$@" >"$OUT" 2>"$ERR" </dev/null
  rc=$?
  [ "$rc" -eq "$want" ] || fail "$(basename "$BIN") $*: exit code $rc, expected $want"
}

# has FILE TEXT: FILE contains TEXT (a fixed string).
has() { grep -F -q -e "$2" "$1" || fail "$(basename "$1") lacks '$2'"; }
