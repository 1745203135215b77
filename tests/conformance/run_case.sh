#!/usr/bin/env bash
# Runs one conformance case and compares its dump with the hand-derived golden file.
#
# usage: run_case.sh MELD_BINARY CASE_DIR NAME
#
# Runs `MELD_BINARY NAME.meld --dump [-- ARGS]` inside CASE_DIR (ARGS: the single line of
# NAME.args, split on blanks, if that file exists) with a 20 s timeout, and compares standard
# output byte for byte with NAME.expected. Exit 0 on a match; otherwise a unified diff
# (expected -> actual) is printed and the exit status is non-zero.
#
# The goldens are derived by hand from the language specification, so UPDATE_GOLDEN=1 never
# rewrites them; it only prints a note.
set -u

if [ "$#" -ne 3 ]; then
  echo "usage: $0 MELD_BINARY CASE_DIR NAME" >&2
  exit 2
fi

meld=$1
dir=$2
name=$3

case "$meld" in
  /*) ;;
  *) meld=$(pwd)/$meld ;;
esac

if [ ! -d "$dir" ]; then
  echo "run_case: no case folder $dir" >&2
  exit 2
fi
cd "$dir" || exit 2

if [ ! -f "$name.meld" ] || [ ! -f "$name.expected" ]; then
  echo "run_case: $name.meld or $name.expected missing in $dir" >&2
  exit 2
fi

if [ "${UPDATE_GOLDEN:-0}" = "1" ]; then
  echo "run_case: note: UPDATE_GOLDEN=1 ignored; $name.expected is hand-derived from the specification and is never rewritten" >&2
fi

args=()
if [ -f "$name.args" ]; then
  read -r -a args < "$name.args" || true
fi

actual=$(mktemp "${TMPDIR:-/tmp}/meld-conf.$name.XXXXXX") || exit 2
errors=$(mktemp "${TMPDIR:-/tmp}/meld-conf.$name.err.XXXXXX") || { rm -f "$actual"; exit 2; }
trap 'rm -f "$actual" "$errors"' EXIT

if [ "${#args[@]}" -gt 0 ]; then
  timeout 20 "$meld" "$name.meld" --dump -- "${args[@]}" > "$actual" 2> "$errors"
else
  timeout 20 "$meld" "$name.meld" --dump > "$actual" 2> "$errors"
fi
status=$?

if [ "$status" -eq 124 ]; then
  echo "run_case: $name: timed out after 20 s" >&2
fi
if [ "$status" -ne 0 ]; then
  echo "run_case: $name: $meld exited with status $status" >&2
  if [ -s "$errors" ]; then
    sed 's/^/  stderr: /' "$errors" >&2
  fi
fi

if cmp -s "$name.expected" "$actual"; then
  if [ "$status" -ne 0 ]; then
    exit 1
  fi
  exit 0
fi

echo "run_case: $name: dump differs from $name.expected" >&2
diff -u --label "$name.expected" --label "$name (actual)" "$name.expected" "$actual"
exit 1
