#!/bin/sh
# meldc command-line cases, one function each: cli.sh MELDC CASE (run from tests/meldc).
set -u
MELDC=$1
CASE=$2
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# The default standard library folder (stdlib/ of the tree) unless a case sets MELD_STDLIB itself.
unset MELD_STDLIB
OUT="$WORK/stdout"
ERR="$WORK/stderr"
BIN=$MELDC
. "$(dirname "$0")/../common/cli_helpers.sh"

case_help() {
  run 0 --help
  has "$OUT" "usage: meldc FILE.meld"
  has "$OUT" "--emit=asm"
  has "$OUT" "exit codes:"
}
case_version() {
  run 0 --version
  has "$OUT" "meldc "
}
case_no_input() {
  run 2
  has "$ERR" "meldc: error: no input file"
}
case_unknown_option() {
  run 2 valid/gradient.meld --frobnicate
  has "$ERR" "unknown option '--frobnicate'"
}
case_bad_define() {
  run 2 valid/gradient.meld -DX=1
  has "$ERR" "bad definition 'X=1'"
}
case_directory_input() {
  run 1 "$WORK"
  has "$ERR" "it is a directory, not a Meld file"
}
case_empty_program() {
  printf '// nothing but a comment\n' >"$WORK/empty.meld"
  run 1 --check "$WORK/empty.meld"
  has "$ERR" "empty.meld:1:1: error: the program is empty: no declaration, rule or fact"
}
case_robots_check() {
  # The check vsim makes when it loads a program for robots, made by meldc --robots too.
  printf 'type linear tap(node, int).\n' >"$WORK/tap.meld"
  run 1 --robots "$WORK/tap.meld" -o "$WORK/tap.mbc"
  has "$ERR" "tap.meld: error: predicate 'tap' must be declared as"
  printf 'type tap(node).\n' >"$WORK/tap.meld"
  run 0 --robots "$WORK/tap.meld" -o "$WORK/tap.mbc"
}
case_emit_bytecode() {
  # default: FILE.mbc next to the input
  cp valid/gradient.meld "$WORK/g.meld"
  run 0 "$WORK/g.meld"
  [ -s "$OUT" ] && fail "bytecode belongs in the .mbc file"
  [ "$(head -c 4 "$WORK/g.mbc")" = "MBC1" ] || fail "g.mbc is not bytecode"
  # the same file (the bytecode names its source files, as given, for file:line in messages)
  run 0 --emit=bytecode "$WORK/g.meld" -o "$WORK/out.mbc"
  cmp -s "$WORK/g.mbc" "$WORK/out.mbc" || fail "-o output differs from the default output"
}
case_output_replaces_file() {
  # An existing output is replaced, not overwritten: a VM running the old .mbc reads its data
  # file's facts from the file's mapping, so the old file (here a second link to it) stays whole.
  cp valid/gradient.meld "$WORK/g.meld"
  printf 'old bytes\n' >"$WORK/g.mbc"
  chmod 640 "$WORK/g.mbc"
  ln "$WORK/g.mbc" "$WORK/old.mbc"
  run 0 "$WORK/g.meld" -o "$WORK/g.mbc"
  [ "$(cat "$WORK/old.mbc")" = "old bytes" ] || fail "the old file was written over"
  [ "$(stat -c %a "$WORK/g.mbc")" = 640 ] || fail "the new file lost the old one's permissions"
  [ "$(head -c 4 "$WORK/g.mbc")" = "MBC1" ] || fail "g.mbc is not the new bytecode"
  ls "$WORK" | grep -q tmp && fail "a temporary file was left: $(ls "$WORK")"
  # Through a symbolic link: the file it names is replaced, the link stays.
  ln -s g.mbc "$WORK/link.mbc"
  run 0 --emit=asm "$WORK/g.meld" -o "$WORK/link.mbc"
  [ -L "$WORK/link.mbc" ] || fail "the symbolic link was replaced"
  has "$WORK/g.mbc" "rule 0"
  # A device is written in place, never replaced.
  run 0 "$WORK/g.meld" -o /dev/null
  [ -c /dev/null ] || fail "/dev/null is no longer a device"
  # A folder that is not there: an error.
  run 1 "$WORK/g.meld" -o "$WORK/missing/g.mbc"
  has "$ERR" "cannot write '$WORK/missing/g.mbc'"
}
case_output_dash() {
  # -o - is standard output, bytecode included (for a pipe), and never a file named '-'.
  cp valid/gradient.meld "$WORK/g.meld"
  (cd "$WORK" && "$BIN" g.meld) || fail "meldc g.meld failed"  # the bytecode names g.meld as given
  (cd "$WORK" && "$BIN" g.meld -o - >"$OUT" 2>"$ERR" </dev/null) || fail "meldc -o - failed"
  cmp -s "$WORK/g.mbc" "$OUT" || fail "-o - did not write the bytecode to standard output"
  [ -e "$WORK/-" ] && fail "-o - wrote a file named '-'"
  run 0 --emit=asm "$WORK/g.meld" -o -
  has "$OUT" "rule 0"
  # Not onto a terminal (script(1), from bsdutils, gives the run one).
  script -qec "'$BIN' '$WORK/g.meld' -o -" /dev/null >"$OUT" 2>&1 </dev/null
  rc=$?
  [ "$rc" -eq 2 ] || fail "bytecode onto a terminal: exit code $rc, expected 2"
  has "$OUT" "refusing to write bytecode to a terminal"
}
case_emit_asm() {
  run 0 --emit=asm valid/gradient.meld
  has "$OUT" "rule 0"
  has "$OUT" "AXIOMS"
}
case_emit_llvm() {
  run 0 --emit=llvm valid/gradient.meld
  has "$OUT" "i32 @meld_block_0(ptr"
  has "$OUT" "target triple"
  run 0 --emit=llvm valid/gradient.meld -o "$WORK/g.ll"
  has "$WORK/g.ll" "@meld_block_0("
}
case_emit_native() {
  cp valid/gradient.meld "$WORK/g.meld"
  run 0 --emit=native "$WORK/g.meld"
  [ -f "$WORK/g.so" ] || fail "no g.so next to g.meld"
  head -c 4 "$WORK/g.so" | grep -q "ELF" || fail "g.so is not an ELF object"
  run 2 --emit=native "$WORK/g.meld" -o -
  has "$ERR" "a shared object cannot go to standard output"
  MELD_LD=/no/such/linker run 1 --emit=native "$WORK/g.meld" -o "$WORK/h.so"
  has "$ERR" "cannot run the linker '/no/such/linker'"
  ls "$WORK"/h.so.*.o.tmp 2>/dev/null && fail "object files were left behind"
  # --cpu: generic by default (the .so runs elsewhere), native, an LLVM name; others refused.
  run 0 --emit=native "$WORK/g.meld" --cpu=x86-64-v2 -o "$WORK/v2.so"
  [ -f "$WORK/v2.so" ] || fail "no v2.so"
  run 0 --emit=llvm "$WORK/g.meld" --cpu=native
  has "$OUT" "@meld_block_0("
  run 2 --emit=native "$WORK/g.meld" --cpu=no-such-cpu -o "$WORK/bad.so"
  has "$ERR" "unknown processor 'no-such-cpu' for --cpu"
  [ -e "$WORK/bad.so" ] && fail "no shared object expected for an unknown processor"
  run 2 --emit=native "$WORK/g.meld" --cpu=
  has "$ERR" "option '--cpu=' needs a processor name"
  true
}
case_emit_native_jobs() {
  # -j: the threads change nothing in the shared object (80 rules: two partitions).
  python3 "$(dirname "$0")/../../bench/native/gen_rules.py" --rules 80 -o "$WORK/rules.meld" >/dev/null
  run 0 --emit=native "$WORK/rules.meld" -j 1 -o "$WORK/r1.so"
  run 0 --emit=native "$WORK/rules.meld" --jobs=3 -o "$WORK/r3.so"
  cmp -s "$WORK/r1.so" "$WORK/r3.so" || fail "-j 1 and --jobs=3 wrote different shared objects"
  for bad in "-j 0" "-jx" "--jobs=" "--jobs=-1"; do
    run 2 --emit=native "$WORK/rules.meld" $bad -o "$WORK/bad.so"
    has "$ERR" "needs a number of threads from 1 to 9999"
  done
  true
}
case_emit_native_progress() {
  # On a terminal (script(1) gives one) a compile longer than a second shows a progress line, which
  # it erases at the end; --no-progress, or stderr that is not a terminal, shows none.
  python3 "$(dirname "$0")/../../bench/native/gen_rules.py" --rules 600 -o "$WORK/big.meld" >/dev/null
  script -qec "'$MELDC' --emit=native -j 1 '$WORK/big.meld' -o '$WORK/big.so'" "$WORK/tty.txt" >/dev/null ||
    fail "meldc failed on a terminal"
  has "$WORK/tty.txt" "meldc: compiling native code: "
  has "$WORK/tty.txt" "parts ("
  script -qec "'$MELDC' --emit=native -j 1 --no-progress '$WORK/big.meld' -o '$WORK/big.so'" "$WORK/quiet.txt" \
    >/dev/null || fail "meldc --no-progress failed on a terminal"
  grep -q "compiling native code" "$WORK/quiet.txt" && fail "--no-progress showed a progress line"
  run 0 --emit=native -j 1 "$WORK/big.meld" -o "$WORK/big.so"
  grep -q "compiling native code" "$ERR" && fail "a progress line on stderr that is not a terminal"
  true
}
case_emit_unsupported() {
  printf 'type edge(node, node).\ndata stanford-snap "g.txt".\n' >"$WORK/d.meld"
  run 1 "$WORK/d.meld"
  has "$ERR" "d.meld:2:1: error: cannot read the data file"
  [ -e "$WORK/d.mbc" ] && fail "no bytecode expected"
  true
}
case_missing_file() {
  run 1 --check no/such/file.meld
  has "$ERR" "meldc: error: cannot read 'no/such/file.meld'"
}
case_emit_ast_to_file() {
  run 0 --emit=ast valid/gradient.meld -o "$WORK/ast.txt"
  [ -s "$OUT" ] && fail "the dump belongs in the -o file"
  has "$WORK/ast.txt" "type route neighbor(node, node, int)"
}
case_define_replaces_const() {
  run 0 --emit=ast valid/header.meld -Dlimit=42 -D newconst=@3
  has "$OUT" "const limit = 42 (from -D)"
  # source node 3 has internal id 1 (see case_emit_nodes_header)
  has "$OUT" "const newconst = @1 (from -D)"
}
case_define_bad_value() {
  run 1 --check valid/header.meld "-Dlimit=1 +"
  has "$ERR" "-Dlimit:1:4: error: unexpected end of file"
}
case_include_dir() {
  run 1 --check cli/uses_stdlib.meld
  has "$ERR" "cannot find included file 'robot.meld'"
  run 0 --check cli/uses_stdlib.meld -I cli/stdlib
  run 0 --check cli/uses_stdlib.meld -Icli/stdlib
}
case_emit_nodes_header() {
  # literals of header.meld: @2 @1 @3; union with the (literal-free) include reverses them:
  # P = [2, 1, 3]; route link: 1->2, 2->3; breadth-first from 2.
  run 0 --emit=nodes valid/header.meld
  printf '0 2\n1 3\n2 1\n' >"$WORK/want"
  diff -u "$WORK/want" "$OUT" || fail "node table differs"
  [ -s "$ERR" ] && fail "unexpected diagnostics"
  run 0 --emit=nodes valid/header.meld -o "$WORK/nodes.txt"
  diff -u "$WORK/want" "$WORK/nodes.txt" || fail "node table in -o file differs"
}
case_emit_nodes_define() {
  # a -D literal not in the program joins the end of nodes(main) = [3, 1, 2, 7]: P = [7, 2, 1, 3]
  run 0 --emit=nodes valid/header.meld -Dnewconst=@7
  printf '0 7\n1 2\n2 3\n3 1\n' >"$WORK/want"
  diff -u "$WORK/want" "$OUT" || fail "node table differs"
}
case_emit_nodes_robots() {
  # --robots: literals @2 @1 @3 keep their ids and every id up to 3 exists (node 0 too)
  run 0 --emit=nodes --robots valid/header.meld
  printf '0 0\n1 1\n2 2\n3 3\n' >"$WORK/want"
  diff -u "$WORK/want" "$OUT" || fail "node table differs"
}
case_emit_nodes_cluster_random() {
  printf 'type linear a(node).\npriority @cluster @random.\na(@1).\n' >"$WORK/r.meld"
  run 0 --emit=nodes "$WORK/r.meld"
  has "$OUT" "0 1"
}
case_help_mentions_nodes() {
  run 0 --help
  has "$OUT" "--emit=nodes"
}
case_stdlib_default() {
  # include #blinkyblocks.meld resolves in the built-in stdlib folder without any -I
  run 0 --check cli/uses_blinkyblocks.meld
  [ -s "$ERR" ] && fail "unexpected diagnostics"
  run 0 --emit=ast cli/uses_blinkyblocks.meld
  has "$OUT" "type route neighbor(node, node, int)"
  has "$OUT" "const top = 5"
}
case_no_stdlib() {
  run 1 --check --no-stdlib cli/uses_blinkyblocks.meld
  has "$ERR" "cli/uses_blinkyblocks.meld:2:1: error: cannot find included file 'blinkyblocks.meld' (searched cli)"
  # with -I the folder list still ends before the stdlib
  run 1 --check cli/uses_blinkyblocks.meld -I cli/stdlib --no-stdlib
  has "$ERR" "(searched cli, cli/stdlib)"
}
case_stdlib_env() {
  # MELD_STDLIB replaces the built-in folder; an empty value means none
  export MELD_STDLIB=cli/stdlib
  run 0 --check cli/uses_stdlib.meld
  run 1 --check cli/uses_blinkyblocks.meld
  has "$ERR" "(searched cli, cli/stdlib)"
  MELD_STDLIB=
  run 1 --check cli/uses_blinkyblocks.meld
  has "$ERR" "(searched cli)"
  unset MELD_STDLIB
}
case_stdlib_after_include_dirs() {
  # a -I folder comes first: its blinkyblocks.meld shadows the stdlib's
  mkdir -p "$WORK/mine"
  printf 'const top = 42.\n' >"$WORK/mine/blinkyblocks.meld"
  printf 'include #blinkyblocks.meld\ntype linear a(node, int).\na(X, top).\n' >"$WORK/p.meld"
  run 0 --emit=ast "$WORK/p.meld" -I "$WORK/mine"
  has "$OUT" "const top = 42"
  run 0 --emit=ast "$WORK/p.meld"
  has "$OUT" "const top = 5"
}
case_help_mentions_no_stdlib() {
  run 0 --help
  has "$OUT" "--no-stdlib"
  has "$OUT" "MELD_STDLIB"
}
case_warnings_keep_exit_zero() {
  run 0 --check cli/warning.meld
  has "$ERR" "warning: persistent predicate 'edge' should be written '!edge(...)'"
}

"case_$CASE"
