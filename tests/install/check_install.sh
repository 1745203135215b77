#!/bin/sh
# `cmake --install` into a fresh prefix, then the installed programs run the examples from there:
# vsim finds the installed BlockCodes by name, meldc the installed standard library (a constant
# added to the installed copy only proves it is that one), the headers and the polling library are
# in place. Usage: check_install.sh CMAKE BUILD_DIR WORK [GUI_ENV...] (GUI_ENV: a command prefix for
# the IDE under the sanitizers, e.g. env LD_PRELOAD=...)
set -u
. "$(dirname "$0")/common.sh"
CMAKE=$1 BUILD=$2 WORK=$3
shift 3
P="$WORK/prefix"
rm -rf "$WORK" && mkdir -p "$WORK"
run_or_fail "$WORK/install.log" "cmake --install" "$CMAKE" --install "$BUILD" --prefix "$P"
expect_files "$P" bin/meldc bin/meld bin/vsim include/simcore/blockcode.h include/simcore/blockcode_polling.h \
         share/meld/stdlib/common.meld share/meld/stdlib/smartblocks.meld lib/meld/blockcodes/color_flood.so \
         lib/meld/libmeld_jit.so lib/meld/libmeld_frontend.so share/meld/examples/worlds/color-flood.xml share/meld/examples/meld/gradient-tap.meld \
         share/man/man1/meldc.1 share/man/man1/meld.1 share/man/man1/vsim.1 \
         share/doc/meld-toolchain/meld-language.md share/doc/meld-toolchain/images/vsim-ide.png
ls "$P"/lib*/libblockcode_polling.a >/dev/null 2>&1 || fail "the polling library was not installed"
unset MELD_STDLIB VSIM_CODE_PATH
cd "$WORK" || exit 1
check_demo "$P" "$WORK/demo"
run_or_fail "$WORK/meld" "the installed vsim did not run a Meld example" \
  "$P/bin/vsim" "$P/share/meld/examples/worlds/meld-gradient-tap.xml" --no-progress --dump
echo "const installedMarker = 1." >>"$P/share/meld/stdlib/common.meld"
printf 'include #blinkyblocks.meld\ntype linear x(node, int).\nx(@0, installedMarker).\n' >"$WORK/marker.meld"
run_or_fail "$WORK/meldc" "the installed meldc did not read the installed standard library" \
  "$P/bin/meldc" --robots --check "$WORK/marker.meld"
# The installed meld loads the installed JIT module for --jit (and only then).
printf 'type linear a(node, int).\na(@0, 1).\na(A, N), N < 3 -o a(A, N + 1).\n' >"$WORK/count.meld"
LD_DEBUG=files "$P/bin/meld" "$WORK/count.meld" --dump --jit >"$WORK/jit" 2>"$WORK/jit.err" ||
  { cat "$WORK/jit.err"; fail "the installed meld --jit failed"; }
grep -q 'a(3)' "$WORK/jit" || fail "the installed meld --jit gave another dump"
grep -q "file=$P/lib/meld/libmeld_jit.so" "$WORK/jit.err" || fail "the installed meld --jit did not load the installed module"
grep -q "file=$P/lib/meld/libmeld_frontend.so" "$WORK/jit.err" ||
  fail "the installed meld did not compile the source with the installed front end module"
# The installed IDE draws the installed Meld example (a picture under Xvfb, as the IDE tests do).
if [ -x "$P/bin/vsim-ide" ]; then
  command -v xvfb-run >/dev/null || fail "xvfb-run is missing (scripts/install-packages.sh installs it)"
  world="$P/share/meld/examples/worlds/meld-gradient-tap.xml"
  run_or_fail "$WORK/ide" "the installed vsim-ide did not draw the example" \
    xvfb-run -a "$@" "$P/bin/vsim-ide" "$world" --screenshot "$WORK/ide.png" --until 3s --size 320x240
  run_or_fail "$WORK/vsim3s" "the installed vsim did not run the example" "$P/bin/vsim" "$world" --until 3s --no-progress
  fp=$(fingerprint "$WORK/vsim3s")
  grep -q "fingerprint $fp" "$WORK/ide" || { cat "$WORK/ide"; fail "the installed vsim-ide ran another run than vsim ($fp)"; }
fi
echo "installed into $P: the demo, a Meld example and the installed stdlib all ran"
