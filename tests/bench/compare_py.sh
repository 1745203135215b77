#!/bin/sh
# bench/compare/compare.py as a program (not timed): with an established compiler that takes
# longer than --compile-timeout, its modes say "compile: timed out" and ours are still measured
# (it used to stop the whole table with a traceback), and the compiler's own children stop with it;
# bad options are refused with exit status 2.
set -u
MELD=$1 MELDC=$2 SCRIPT=$3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir "$WORK/anchors"
# A compiler that is a script around a compiler process, as the established one is: a timeout
# must stop both (the child would leave its mark after 3 s).
cat > "$WORK/anchors/meldc-ref" <<SH
#!/bin/sh
sh -c 'sleep 3; touch "\$0"' "$WORK/survived" &
sleep 20
SH
printf '#!/bin/sh\nexit 1\n' > "$WORK/anchors/meld-ref"
chmod +x "$WORK/anchors/meldc-ref" "$WORK/anchors/meld-ref"
cat > "$WORK/ring.meld" <<'MELD'
type route edge(node, node).
type linear token(node, int).
!edge(@0, @1). !edge(@1, @0).
token(@0, 0).
token(A, N), N < 20, !edge(A, B) -o token(B, N + 1).
MELD
start=$(date +%s)
# (--modes separated by a space here, by a comma below: suite.sh takes them the first way.)
MELD="$MELD" MELDC="$MELDC" python3 "$SCRIPT" --anchors "$WORK/anchors" --modes "bc ref1" --runs 1 \
  --compile-timeout 1 "$WORK/ring.meld" > "$WORK/table.md" 2> "$WORK/err.txt" ||
  fail "compare.py failed: $(cat "$WORK/err.txt")"
[ $(( $(date +%s) - start )) -lt 15 ] || fail "the compile was not cut at --compile-timeout"
sleep 4
[ ! -e "$WORK/survived" ] || fail "the compiler's child outlived the timeout"
grep -q '^| ring | [0-9.]* | compile: timed out after 1 s | - | - |$' "$WORK/table.md" ||
  fail "no row with our time and the timed-out compile: $(cat "$WORK/table.md")"
python3 "$SCRIPT" --anchors "$WORK/anchors" --modes bc,nope "$WORK/ring.meld" > /dev/null 2>&1
[ $? -eq 2 ] || fail "an unknown mode is not refused with status 2"
python3 "$SCRIPT" --modes bc > /dev/null 2>&1
[ $? -eq 2 ] || fail "no program is not refused with status 2"
exit 0
