#!/bin/sh
# `meld` command-line cases, one function each: cli.sh MELD CASE.
set -u
MELD=$1
CASE=$2
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
OUT="$WORK/stdout"
ERR="$WORK/stderr"
BIN=$MELD
. "$(dirname "$0")/../common/cli_helpers.sh"

cat >"$WORK/roll.meld" <<'MELD'
type linear roll(node, int).
type linear here(node).
roll(A, randint(1000000)).
here(@0). here(@1). here(@2).
MELD

cat >"$WORK/reach.meld" <<'MELD'
type route edge(node, node).
type reach(node, min int).
!edge(@0, @1). !edge(@1, @2). !edge(@2, @3). !edge(@3, @0). !edge(@1, @3).
!reach(@0, 0).
!reach(A, D), !edge(A, B) -o !reach(B, D + 1).
MELD

case_seed() {
  # The same seed gives the same draws, another seed others.
  run 0 "$WORK/roll.meld" --dump --seed 5
  cp "$OUT" "$WORK/a"
  run 0 "$WORK/roll.meld" --dump --seed 5
  cmp -s "$OUT" "$WORK/a" || fail "--seed 5 twice gave two dumps"
  run 0 "$WORK/roll.meld" --dump --seed 6
  cmp -s "$OUT" "$WORK/a" && fail "--seed 5 and --seed 6 gave the same dump"
  run 2 "$WORK/roll.meld" --seed -1
  has "$ERR" "--seed expects a non-negative integer, got '-1'"
}

case_max_steps() {
  printf 'type linear a(node, int).\na(@0, 0).\na(A, N) -o a(A, N + 1).\n' >"$WORK/forever.meld"
  run 4 "$WORK/forever.meld" --max-steps 1000
  has "$ERR" "stopped after 1000 steps (the step limit"
}

case_why() {
  # The derivation tree of a fact (issue 11, point 6): equal to the expected tree, each rule step
  # and axiom at its FILE:LINE (the program is named relative to its folder: stable paths).
  cd "$(dirname "$0")/programs" || fail "no programs folder"
  run 0 why-reach.meld --why 'reach(@0, 3)' --why '!edge(@2,@1)'
  cmp -s "$OUT" why-reach.expected || { diff why-reach.expected "$OUT"; fail "the tree differs from why-reach.expected"; }
  run 5 why-reach.meld --why 'reach(@0, 7)'
  has "$ERR" "no derivation of reach(@0, 7): the run did not derive it"
  run 2 why-reach.meld --why 'nosuch(@0, 7)'
  has "$ERR" "the program has no predicate 'nosuch'"
  run 2 why-reach.meld --why 'reach(0, 7)'
  has "$ERR" "the first argument is the node"
  run 2 why-reach.meld --why
  has "$ERR" "needs a fact"
}

case_aggregate_cascade() {
  # Passing values of sum aggregates must not cascade (issue 10, point 11): a few thousand steps,
  # where without the established VM's cancellation rule it took over two million.
  run 0 "$(dirname "$0")/programs/layered-training.meld" --stats --max-steps 5000
  has "$ERR" "facts derived: 751"
}

case_deep_recursion() {
  # A runaway recursive `fun` is a run-time error, not a stack overflow (found by fuzzing under
  # ASan); a deep but bounded one still runs.
  printf 'type linear a(node, int).\nfun down(int X) : int = if X <= 0 then 0 else 1 + down(X - 1) end.\na(@0, down(100000000)).\n' >"$WORK/rec.meld"
  run 4 "$WORK/rec.meld"
  has "$ERR" "function 'down' nested"
  has "$ERR" "runaway recursion?"
  printf 'type linear a(node, int).\nfun down(int X) : int = if X <= 0 then 0 else 1 + down(X - 1) end.\na(@0, down(500)).\n' >"$WORK/ok.meld"
  run 0 "$WORK/ok.meld" --dump
  has "$OUT" "a(500)"
}

case_directory_input() {
  run 1 "$WORK"
  has "$ERR" "it is a directory, not a Meld file"
}

case_help() {
  run 0 --help
  has "$OUT" "--seed S"
  has "$OUT" "--max-steps N"
  has "$OUT" "-j N, --threads N"
  has "$OUT" "--profile FILE.json"
}

case_threads() {
  # -j N gives the serial dump of a program that does not depend on the schedule, prints the
  # per-thread table with --stats, and refuses a bad count and --why.
  run 0 "$WORK/reach.meld" --dump
  cp "$OUT" "$WORK/serial"
  run 0 "$WORK/reach.meld" --dump -j 3 --stats
  cmp -s "$OUT" "$WORK/serial" || fail "-j 3 and the serial VM gave two dumps"
  has "$ERR" "threads: 3"
  has "$ERR" "busy %"
  # The VM's memory by part adds up to its total (all threads together).
  has "$ERR" "VM MB by part: fact tables "
  awk -F'[:,] *' '/^VM MB: / {total = $2}
    /^VM MB by part:/ {for (i = 2; i <= NF; ++i) {n = split($i, w, " "); sum += w[n]}; seen = 1}
    END {d = total - sum; if (!seen || d > 0.3 || d < -0.3) exit 1}' "$ERR" ||
    fail "the VM's memory by part does not add up to its total"
  run 0 "$WORK/reach.meld" --dump --threads 2
  cmp -s "$OUT" "$WORK/serial" || fail "--threads 2 and the serial VM gave two dumps"
  run 2 "$WORK/reach.meld" -j 0
  has "$ERR" "-j/--threads expects a thread count from 1 to 1024, got '0'"
  run 2 "$WORK/reach.meld" -j two
  has "$ERR" "got 'two'"
  run 2 "$WORK/reach.meld" -j 2 --why 'reach(@1, 1)'
  has "$ERR" "--why records derivations in serial runs only"
}

case_profile() {
  # --profile writes a Chrome trace: a name per worker thread, spans of node runs, counters.
  run 0 "$WORK/roll.meld" -j 2 --profile "$WORK/p.json"
  has "$WORK/p.json" '"traceEvents"'
  has "$WORK/p.json" '"name":"worker 0"'
  has "$WORK/p.json" '"name":"worker 1"'
  has "$WORK/p.json" '"name":"node runs"'
  has "$WORK/p.json" '"facts derived per ms, thread 0"'
  has "$WORK/p.json" '"name":"idle"'
  if command -v python3 >/dev/null; then
    python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$WORK/p.json" || fail "--profile wrote invalid JSON"
  fi
  run 2 "$WORK/roll.meld" --profile "$WORK/no/such/dir/p.json"
  has "$ERR" "--profile: cannot write"
}

case_jit() {
  # Native code gives the bytecode's dump, its run-time errors unwind through it with the same
  # message and exit status, and --help says so.
  run 0 "$WORK/reach.meld" --dump
  cp "$OUT" "$WORK/bytecode"
  run 0 "$WORK/reach.meld" --dump --jit
  cmp -s "$OUT" "$WORK/bytecode" || fail "--jit gave another dump"
  has "$OUT" "!reach(2)"
  printf 'type linear go(node, int).\ntype linear r(node, int).\ngo(@0, 0).\ngo(A, N) -o r(A, 10 / N).\n' >"$WORK/div.meld"
  run 4 "$WORK/div.meld" --jit
  has "$ERR" "integer division by zero"
  run 0 --help
  has "$OUT" "--jit"
}

case_no_scheduling() {
  # --no-scheduling (the established VM's -n): set-priority and stop-program do nothing. Node 1
  # pings nodes 2, 3, 4 and asks them priority 5 (applied: node 4 runs first); without
  # coordination they run in FIFO order, and the stop-program of node 4 is ignored.
  cat >"$WORK/prio.meld" <<'MELD'
type linear t(node).
type linear go(node).
type linear ping(node).
type linear log(node, int).
type linear cnt(node, int).
type linear seen(node, int, int).
priority @order @desc.
t(@4). t(@3). t(@2).
go(@1).
cnt(@0, 0).
go(A) -o ping(@2), ping(@3), ping(@4), set-priority(@2, 5.0), set-priority(@3, 5.0), set-priority(@4, 5.0).
ping(A) -o log(@0, node2int(A)), (if node2int(A) = 4 then stop-program(A) otherwise 1 end).
log(A, X), cnt(A, N) -o seen(A, X, N), cnt(A, N + 1).
MELD
  # With coordination node 4 runs first and stops the program: its log waits at node 0.
  run 0 "$WORK/prio.meld" --dump
  has "$OUT" "log(4)"
  has "$OUT" "cnt(0)"
  run 0 "$WORK/prio.meld" --dump --no-scheduling
  has "$OUT" "seen(2, 0)"
  has "$OUT" "seen(3, 1)"
  has "$OUT" "seen(4, 2)"
  has "$OUT" "cnt(3)"
  run 0 --help
  has "$OUT" "--no-scheduling"
}

case_jit_module() {
  # The LLVM backend is a module loaded only for --jit (meldc/jit_loader.hpp): meld does not link
  # LLVM, runs bytecode without the module, and says what is wrong with a missing or foreign one.
  command -v ldd >/dev/null && ldd "$MELD" | grep -q libLLVM && fail "meld links libLLVM"
  LD_DEBUG=files "$MELD" "$WORK/reach.meld" --dump >"$OUT" 2>"$ERR" || fail "a bytecode run failed"
  grep -q 'libLLVM' "$ERR" && fail "a bytecode run loaded libLLVM"
  LD_DEBUG=files "$MELD" "$WORK/reach.meld" --dump --jit >"$OUT" 2>"$ERR" || fail "a --jit run failed"
  grep -q 'libmeld_jit.so' "$ERR" || fail "--jit did not load libmeld_jit.so"
  export MELD_JIT_MODULE="$WORK/none.so"
  run 0 "$WORK/reach.meld" --dump
  has "$OUT" "!reach(2)"
  run 4 "$WORK/reach.meld" --jit
  has "$ERR" "MELD_JIT_MODULE names $WORK/none.so, which does not exist"
  printf 'not an object' >"$WORK/none.so"
  run 4 "$WORK/reach.meld" --jit
  has "$ERR" "cannot load the native code module $WORK/none.so"
  export MELD_JIT_MODULE="$BLOCKCODE"
  run 4 "$WORK/reach.meld" --jit
  has "$ERR" "is not a native code module of this toolchain"
  unset MELD_JIT_MODULE
}

case_frontend_module() {
  # Meld source goes through the front end module (meldc/frontend_loader.hpp): meld does not
  # link the ANTLR runtime, runs bytecode without loading it, and says what is wrong with a
  # missing or foreign module (status 1, as for a program that does not compile).
  command -v ldd >/dev/null && ldd "$MELD" | grep -q libantlr4 && fail "meld links the ANTLR runtime"
  "$MELDC" "$WORK/reach.meld" -o "$WORK/reach.mbc" || fail "meldc failed on reach.meld"
  LD_DEBUG=files "$MELD" "$WORK/reach.mbc" --dump >"$OUT" 2>"$ERR" || fail "a bytecode run failed"
  grep -q 'libantlr4\|libmeld_frontend' "$ERR" && fail "a bytecode run loaded the front end"
  cp "$OUT" "$WORK/bytecode"
  LD_DEBUG=files "$MELD" "$WORK/reach.meld" --dump >"$OUT" 2>"$ERR" || fail "a source run failed"
  grep -q 'libmeld_frontend.so' "$ERR" || fail "a source run did not load libmeld_frontend.so"
  cmp -s "$OUT" "$WORK/bytecode" || fail "the source run gave another dump than its bytecode"
  printf 'type linear a(node, int).\na(@0, 1) oops\n' >"$WORK/bad.meld"
  run 1 "$WORK/bad.meld"
  has "$ERR" "bad.meld:2:10: error: unexpected name 'oops'"
  export MELD_FRONTEND_MODULE="$WORK/none.so"
  run 0 "$WORK/reach.mbc" --dump
  run 1 "$WORK/reach.meld"
  has "$ERR" "MELD_FRONTEND_MODULE names $WORK/none.so, which does not exist"
  printf 'not an object' >"$WORK/none.so"
  run 1 "$WORK/reach.meld"
  has "$ERR" "cannot load the Meld front end module $WORK/none.so"
  export MELD_FRONTEND_MODULE="$BLOCKCODE"
  run 1 "$WORK/reach.meld"
  has "$ERR" "is not a Meld front end module of this toolchain"
  unset MELD_FRONTEND_MODULE
}

case_pipe_input() {
  # Bytecode through a named pipe (read once, as a stream): the dump of the file itself. meld once
  # read the pipe's first bytes to see whether it was a shared object, then waited for a writer
  # that had gone: hence the timeout.
  "$MELDC" "$WORK/reach.meld" -o "$WORK/reach.mbc" || fail "meldc failed"
  run 0 "$WORK/reach.mbc" --dump
  cp "$OUT" "$WORK/from_file"
  mkfifo "$WORK/pipe.mbc" || fail "mkfifo failed"
  cat "$WORK/reach.mbc" >"$WORK/pipe.mbc" &
  writer=$!
  timeout 30 "$MELD" "$WORK/pipe.mbc" --dump >"$OUT" 2>"$ERR" </dev/null
  rc=$?
  kill "$writer" 2>/dev/null
  [ "$rc" -eq 0 ] || fail "meld on a pipe: exit code $rc (124: it did not finish in 30 s)"
  cmp -s "$OUT" "$WORK/from_file" || fail "the pipe gave another dump than the file"
  has "$OUT" "reach(2)"
}

case_native() {
  # meldc --emit=native, then meld FILE.so: the bytecode's dump. Files that are not native Meld
  # programs, or were built for another version, are refused with exit status 3.
  run 0 "$WORK/reach.meld" --dump
  cp "$OUT" "$WORK/bytecode"
  "$MELDC" --emit=native "$WORK/reach.meld" || fail "meldc --emit=native failed"
  [ -f "$WORK/reach.so" ] || fail "no reach.so next to reach.meld"
  run 0 "$WORK/reach.so" --dump
  cmp -s "$OUT" "$WORK/bytecode" || fail "reach.so gave another dump"
  run 0 "$WORK/reach.so" --dump -j 2
  # A run-time error thrown by a helper unwinds through the shared object's code (its unwind
  # tables are found: ld --eh-frame-hdr), serially and on threads: a message and status 4.
  printf 'type linear go(node, int).\ntype linear r(node, int).\ngo(@0, 0).\ngo(A, N) -o r(A, 10 / N).\n' >"$WORK/div.meld"
  "$MELDC" --emit=native --no-progress "$WORK/div.meld" || fail "meldc --emit=native failed on div.meld"
  run 4 "$WORK/div.so"
  has "$ERR" "integer division by zero"
  run 4 "$WORK/div.so" -j 2
  has "$ERR" "integer division by zero"
  run 2 "$WORK/reach.so" --jit
  has "$ERR" "native code already"
  run 3 "$FAKES/fake_abi.so"
  has "$ERR" "built for native ABI version"
  has "$ERR" ": compile the program again with this meldc"
  run 3 "$FAKES/fake_bytecode.so"
  has "$ERR" "its bytecode is bad"
  run 3 "$FAKES/fake_magic.so"
  has "$ERR" "not a native Meld program (bad description)"
  run 3 "$BLOCKCODE"
  has "$ERR" "not a native Meld program (no meld_native_program"
  printf 'not an object' >"$WORK/text.so"
  run 3 "$WORK/text.so"
  has "$ERR" "cannot load the shared object"
  # A program of two partitions (two object files; meldc_native's partitionBlocks): every rule of
  # the chain must run, in the .so and in the JIT.
  python3 "$(dirname "$0")/../../bench/native/gen_rules.py" --rules 80 -o "$WORK/chain.meld" >/dev/null
  "$MELDC" --emit=native "$WORK/chain.meld" || fail "meldc --emit=native failed on chain.meld"
  run 0 "$WORK/chain.so" --dump
  has "$OUT" "p80(80, 156)"
  cp "$OUT" "$WORK/chain.dump"
  run 0 "$WORK/chain.meld" --jit --dump
  cmp -s "$OUT" "$WORK/chain.dump" || fail "chain.meld --jit gave another dump than chain.so"
}

case_native_step_limit() {
  # Native code counts a run's steps as the interpreter does (it begins most loops itself, from
  # native_abi.h's meld_native_context): the fewest --max-steps a run completes under is the
  # bytecode's for the shared object and the JIT too, and one less stops each of them.
  printf 'type linear a(node, int).\ntype b(node, int).\n!b(@0, 1). !b(@1, 2).\na(@0, 0). a(@1, 0).\na(A, N), !b(A, K), N < 40 -o a(A, N + K).\n' >"$WORK/count.meld"
  "$MELDC" --emit=native --no-progress "$WORK/count.meld" || fail "meldc --emit=native failed on count.meld"
  lo=1
  hi=100000
  "$MELD" "$WORK/count.meld" --max-steps $hi >/dev/null 2>&1 || fail "count.meld did not end within $hi steps"
  while [ $((hi - lo)) -gt 1 ]; do
    mid=$(((lo + hi) / 2))
    if "$MELD" "$WORK/count.meld" --max-steps $mid >/dev/null 2>&1; then hi=$mid; else lo=$mid; fi
  done
  for program in "$WORK/count.so" "$WORK/count.meld --jit"; do
    run 0 $program --max-steps $hi
    run 4 $program --max-steps $lo
    has "$ERR" "stopped after $lo steps"
  done
}

case_native_why() {
  # Native code updates, derives and sends facts itself (native_abi.h's meld_native_context)
  # unless derivations are being recorded: --why gives the bytecode's trees for the shared object
  # and the JIT, for a fact updated in place (count), one derived (seen) and one sent (token).
  cat >"$WORK/ring.meld" <<'RING'
type route edge(node, node).
type linear count(node, int).
type linear token(node, int).
type linear seen(node, int).
!edge(@0, @1). !edge(@1, @2). !edge(@2, @0).
count(@0, 0). count(@1, 0). count(@2, 0).
token(@0, 0).
token(A, N), count(A, C), N < 7, !edge(A, B) -o count(A, C + 1), seen(A, N), token(B, N + 1).
RING
  "$MELDC" --emit=native --no-progress "$WORK/ring.meld" || fail "meldc --emit=native failed on ring.meld"
  "$MELDC" --emit=asm "$WORK/ring.meld" >"$WORK/ring.asm" || fail "meldc --emit=asm failed on ring.meld"
  for op in UPDATE DERIVE SEND; do has "$WORK/ring.asm" " $op "; done
  set -- --why 'count(@1, 3)' --why 'seen(@2, 4)' --why 'token(@2, 7)'
  run 0 "$WORK/ring.meld" "$@"
  has "$OUT" "sent to @2 as a message"
  cp "$OUT" "$WORK/trees"
  run 0 "$WORK/ring.so" "$@"
  cmp -s "$OUT" "$WORK/trees" || { diff "$WORK/trees" "$OUT"; fail "ring.so gave other trees"; }
  run 0 "$WORK/ring.meld" --jit "$@"
  cmp -s "$OUT" "$WORK/trees" || { diff "$WORK/trees" "$OUT"; fail "ring.meld --jit gave other trees"; }
}

"case_$CASE"
