# Sourced by run-b4.sh and calibrate.sh: what both need (with bench/common.sh: usage, median).
. "$(dirname "${BASH_SOURCE[0]}")/../common.sh"
# field KEY FILE: the value of a "KEY: value" line of `meld --stats`.
field() { awk -v k="$1" 'index($0, k ": ") == 1 { print substr($0, length(k) + 3) }' "$2"; }
# b2_programs REPO QUICK ONLY: generates the B2 programs (bench/meld/run-b2.sh) and prints their
# paths, one per line. QUICK: "--quick" or ""; ONLY: a list of program names or "".
b2_programs() {
  local args=(--generate-only)
  [ -n "$2" ] && args+=(--quick)
  [ -n "$3" ] && args+=(--only "$3")
  "$1/bench/meld/run-b2.sh" "${args[@]}" | grep '\.meld$'
}
