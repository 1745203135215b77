#!/bin/sh
# Golden tests of meldc, run by CTest from tests/meldc (so file names in diagnostics are relative).
#   golden.sh MELDC error FILE.meld   meldc --check must exit 1 and print exactly FILE.expected on
#                                     stderr (nothing on stdout)
#   golden.sh MELDC valid FILE.meld   meldc --check must exit 0 silently; if FILE.ast exists,
#                                     meldc --emit=ast must print exactly that
# UPDATE_GOLDEN=1 rewrites the .expected / .ast files instead of comparing.
set -u
# The standard library folder as a path relative to tests/meldc, so that "cannot find included
# file" diagnostics (which list it) are the same in every checkout.
export MELD_STDLIB=../../stdlib
MELDC=$1
KIND=$2
FILE=$3
BASE=${FILE%.meld}
OUT=$(mktemp)
ERR=$(mktemp)
trap 'rm -f "$OUT" "$ERR"' EXIT

fail() {
  echo "FAIL: $*"
  echo "--- stdout"; cat "$OUT"
  echo "--- stderr"; cat "$ERR"
  exit 1
}

case $KIND in
  error)
    "$MELDC" --check "$FILE" >"$OUT" 2>"$ERR" </dev/null
    rc=$?
    if [ "${UPDATE_GOLDEN:-0}" = 1 ]; then cp "$ERR" "$BASE.expected"; echo "updated $BASE.expected"; exit 0; fi
    [ "$rc" -eq 1 ] || fail "exit code $rc, expected 1"
    [ -s "$OUT" ] && fail "unexpected output on stdout"
    diff -u "$BASE.expected" "$ERR" || fail "diagnostics differ from $BASE.expected"
    ;;
  valid)
    "$MELDC" --check "$FILE" >"$OUT" 2>"$ERR" </dev/null
    rc=$?
    [ "$rc" -eq 0 ] || fail "exit code $rc, expected 0"
    [ -s "$ERR" ] && fail "unexpected diagnostics"
    if [ -f "$BASE.ast" ] || [ "${UPDATE_GOLDEN:-0}" = 1 ]; then
      "$MELDC" --emit=ast "$FILE" >"$OUT" 2>"$ERR" </dev/null || fail "--emit=ast failed"
      if [ "${UPDATE_GOLDEN:-0}" = 1 ]; then
        [ -f "$BASE.ast" ] && cp "$OUT" "$BASE.ast" && echo "updated $BASE.ast"
        exit 0
      fi
      diff -u "$BASE.ast" "$OUT" || fail "AST dump differs from $BASE.ast"
    fi
    ;;
  *) echo "unknown kind $KIND"; exit 2 ;;
esac
exit 0
