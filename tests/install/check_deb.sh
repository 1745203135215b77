#!/bin/sh
# The Debian package: `cpack -G DEB` from the build, its declared dependencies, then unpacked into a
# throw-away root (dpkg-deb -x) and run from there: the demo with the packaged BlockCode, a Meld
# program compiled by the packaged meldc with the packaged stdlib to native code (ld, a declared
# dependency) and run by the packaged meld, and a man page.
# Usage: check_deb.sh CPACK BUILD_DIR WORK
set -u
. "$(dirname "$0")/common.sh"
CPACK=$1 BUILD=$2 WORK=$3
rm -rf "$WORK" && mkdir -p "$WORK"
run_or_fail "$WORK/cpack.log" "cpack -G DEB" "$CPACK" -G DEB --config "$BUILD/CPackConfig.cmake" -B "$WORK/pkg"
DEB=$(ls "$WORK"/pkg/meld-toolchain_*_*.deb 2>/dev/null | head -1)
[ -n "$DEB" ] || { cat "$WORK/cpack.log"; fail "no meld-toolchain_*.deb made"; }

DEPENDS=$(dpkg-deb -f "$DEB" Depends)
for needed in binutils libllvm19 libqt6widgets6 libpugixml1v5 libantlr4-runtime4.9 libstdc++6; do
  echo "$DEPENDS" | grep -q "\\b$needed\\b" || fail "Depends lacks $needed: $DEPENDS"
done
# Every declared dependency is a package this machine (which ran the package's programs) has.
echo "$DEPENDS" | tr ',' '\n' | sed 's/[(|].*//; s/ //g' | while read -r dep; do
  [ -z "$dep" ] && continue
  dpkg-query -W -f='${Status}' "$dep" 2>/dev/null | grep -q "install ok installed" ||
    { echo "FAIL: declared dependency $dep is not a package installed here"; exit 1; }
done || exit 1

R="$WORK/root"
U="$R/usr"
dpkg-deb -x "$DEB" "$R" || fail "dpkg-deb -x"
expect_files "$R" usr/bin/meldc usr/bin/meld usr/bin/vsim usr/bin/vsim-ide usr/share/meld/stdlib/common.meld \
         usr/lib/meld/blockcodes/color_flood.so usr/lib/meld/libmeld_jit.so usr/lib/meld/libmeld_frontend.so usr/include/simcore/blockcode.h \
         usr/lib/cmake/MeldToolchain/MeldToolchainConfig.cmake usr/lib/pkgconfig/meld-blockcode.pc \
         usr/share/man/man1/vsim.1 usr/share/meld/examples/worlds/color-flood.xml
unset MELD_STDLIB VSIM_CODE_PATH
cd "$WORK" || exit 1
check_demo "$U" "$WORK/demo"
run_or_fail "$WORK/meldc" "the packaged meldc did not compile to native code with the packaged stdlib" \
  "$U/bin/meldc" --robots --emit=native --no-progress -o "$WORK/rainbow.so" "$U/share/meld/examples/meld/rainbow.meld"
world="$U/share/meld/examples/worlds/meld-rainbow.xml"
run_or_fail "$WORK/native" "the packaged vsim did not run the native program" \
  "$U/bin/vsim" "$world" --program "$WORK/rainbow.so" --no-progress
run_or_fail "$WORK/bytecode" "the packaged vsim did not run the Meld example" "$U/bin/vsim" "$world" --no-progress
[ "$(fingerprint "$WORK/native")" = "$(fingerprint "$WORK/bytecode")" ] ||
  fail "native and bytecode runs differ: $(fingerprint "$WORK/native") / $(fingerprint "$WORK/bytecode")"
# vsim --jit from the package loads the packaged JIT module.
LD_DEBUG=files "$U/bin/vsim" "$world" --jit --no-progress >"$WORK/jit" 2>"$WORK/jit.err" ||
  { cat "$WORK/jit.err"; fail "the packaged vsim --jit failed"; }
grep -q "file=$U/lib/meld/libmeld_jit.so" "$WORK/jit.err" || fail "the packaged vsim --jit did not load the packaged module"
[ "$(fingerprint "$WORK/jit")" = "$(fingerprint "$WORK/bytecode")" ] || fail "the packaged vsim --jit ran another run"
MANWIDTH=80 man -l "$U/share/man/man1/vsim.1" 2>/dev/null | grep -q "simulate modular robots" ||
  fail "the packaged man page vsim.1 does not render"
echo "$(basename "$DEB"): $(du -k "$DEB" | cut -f1) KiB, unpacked into $R: demo, native Meld and man page ran"
