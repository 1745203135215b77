#!/bin/sh
# B1's executable as a program (not timed): on 3,000 blocks for 300 s the plain flood dies in its
# first cluster while --epidemic reaches every block; a run is the same twice; --json carries the
# reached-over-time samples; bad options are refused.
set -u
BIN=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
field() { sed -n "s/.*\"$1\":\([^,}]*\).*/\1/p" "$2"; }

"$BIN" --blocks 3000 --until 300s --json --no-progress >"$WORK/plain.json" || fail "plain run failed"
"$BIN" --blocks 3000 --until 300s --epidemic --json --no-progress >"$WORK/epi.json" || fail "epidemic run failed"
"$BIN" --blocks 3000 --until 300s --epidemic --json --no-progress >"$WORK/epi2.json" || fail "second epidemic run failed"
[ "$(field flooded "$WORK/epi.json")" = 3000 ] || fail "the epidemic reached $(field flooded "$WORK/epi.json") of 3000"
plain=$(field flooded "$WORK/plain.json")
[ "$plain" -lt 3000 ] || fail "the plain flood reached every block ($plain): the world is not B1's"
[ "$(field epidemic "$WORK/epi.json")" = true ] && [ "$(field epidemic "$WORK/plain.json")" = false ] ||
  fail "the json does not say which variant ran"
grep -q '"reached":\[\[30.0,[0-9]*\],\[60.0,' "$WORK/epi.json" || fail "no reached-over-time samples"
grep -q '\[300.0,3000\]\]' "$WORK/epi.json" || fail "the last sample is not all 3000 blocks"
[ "$(field fingerprint "$WORK/epi.json")" = "$(field fingerprint "$WORK/epi2.json")" ] ||
  fail "two epidemic runs differ"
[ "$(field fingerprint "$WORK/epi.json")" != "$(field fingerprint "$WORK/plain.json")" ] ||
  fail "the epidemic run has the plain run's fingerprint"
"$BIN" --epidemic=yes 2>"$WORK/err" && fail "--epidemic=yes accepted"
grep -q "unknown option '--epidemic=yes'" "$WORK/err" || fail "no message for a bad option"
echo ok
