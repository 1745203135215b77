#!/bin/sh
# `cmake --install` into a fresh prefix, then the installed programs run the examples from there:
# vsim finds the installed BlockCodes by name, meldc the installed standard library (a constant
# added to the installed copy only proves it is that one), the headers and the polling library are
# in place. Usage: check_install.sh CMAKE BUILD_DIR WORK [GUI_ENV...] (GUI_ENV: a command prefix for
# the IDE under the sanitizers, e.g. env LD_PRELOAD=...)
set -u
CMAKE=$1 BUILD=$2 WORK=$3
shift 3
P="$WORK/prefix"
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$WORK" && mkdir -p "$WORK"
"$CMAKE" --install "$BUILD" --prefix "$P" >"$WORK/install.log" 2>&1 || { cat "$WORK/install.log"; fail "cmake --install"; }
for f in bin/meldc bin/meld bin/vsim include/simcore/blockcode.h include/simcore/blockcode_polling.h \
         share/meld/stdlib/common.meld share/meld/stdlib/smartblocks.meld lib/meld/blockcodes/color_flood.so \
         share/meld/examples/worlds/color-flood.xml share/meld/examples/meld/gradient-tap.meld \
         share/man/man1/meldc.1 share/man/man1/meld.1 share/man/man1/vsim.1 \
         share/doc/meld-toolchain/meld-language.md share/doc/meld-toolchain/images/vsim-ide.png; do
  [ -e "$P/$f" ] || fail "$f was not installed"
done
ls "$P"/lib*/libblockcode_polling.a >/dev/null 2>&1 || fail "the polling library was not installed"
unset MELD_STDLIB VSIM_CODE_PATH
cd "$WORK" || exit 1
"$P/bin/vsim" "$P/share/meld/examples/worlds/color-flood.xml" --no-progress >"$WORK/out" 2>"$WORK/err" ||
  { cat "$WORK/err"; fail "the installed vsim did not run the demo"; }
grep -q "block code      color-flood ($P/lib/meld/blockcodes/color_flood.so)" "$WORK/out" ||
  { cat "$WORK/out"; fail "the demo did not run the installed BlockCode"; }
"$P/bin/vsim" "$P/share/meld/examples/worlds/meld-gradient-tap.xml" --no-progress --dump >"$WORK/meld" 2>&1 ||
  { cat "$WORK/meld"; fail "the installed vsim did not run a Meld example"; }
echo "const installedMarker = 1." >>"$P/share/meld/stdlib/common.meld"
printf 'include #blinkyblocks.meld\ntype linear x(node, int).\nx(@0, installedMarker).\n' >"$WORK/marker.meld"
"$P/bin/meldc" --robots --check "$WORK/marker.meld" >"$WORK/meldc" 2>&1 ||
  { cat "$WORK/meldc"; fail "the installed meldc did not read the installed standard library"; }
# The installed IDE draws the installed Meld example (a picture under Xvfb, as the IDE tests do).
if [ -x "$P/bin/vsim-ide" ]; then
  command -v xvfb-run >/dev/null || fail "xvfb-run is missing (scripts/install-packages.sh installs it)"
  xvfb-run -a "$@" "$P/bin/vsim-ide" "$P/share/meld/examples/worlds/meld-gradient-tap.xml" --screenshot "$WORK/ide.png" \
    --until 3s --size 320x240 >"$WORK/ide" 2>&1 || { cat "$WORK/ide"; fail "the installed vsim-ide did not draw the example"; }
  fp=$("$P/bin/vsim" "$P/share/meld/examples/worlds/meld-gradient-tap.xml" --until 3s --no-progress | awk '/fingerprint/ {print $2}')
  grep -q "fingerprint $fp" "$WORK/ide" || { cat "$WORK/ide"; fail "the installed vsim-ide ran another run than vsim ($fp)"; }
fi
echo "installed into $P: the demo, a Meld example and the installed stdlib all ran"
