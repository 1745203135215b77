#!/bin/sh
# examples/blockcode-project built outside the tree against the installation that install.prefix
# made (fixture): once with CMake (find_package(MeldToolchain), meld_add_blockcode), once with
# pkg-config and the C compiler alone; both shared objects run the project's world in the installed
# vsim with the same result, and the centre of the cross shows six neighbours (white).
# Usage: check_blockcode_project.sh CMAKE SOURCE_DIR WORK (WORK/prefix: the installation)
set -u
. "$(dirname "$0")/common.sh"
CMAKE=$1 SRC=$2 WORK=$3
P="$WORK/prefix" B="$WORK/project"
[ -x "$P/bin/vsim" ] || fail "no installation in $P (install.prefix runs first)"
rm -rf "$B" && mkdir -p "$B"
cp -r "$SRC/examples/blockcode-project" "$B/src"
# A polling BlockCode too (MeldToolchain::blockcode_polling, the exported static library).
echo "meld_add_blockcode(wave_polling \"$P/share/meld/examples/c/wave_polling.c\" POLLING)" >>"$B/src/CMakeLists.txt"
# The package's folder variables name the installation's folders.
cat >>"$B/src/CMakeLists.txt" <<'CMAKE'
foreach(f "${MeldToolchain_INCLUDE_DIR}/simcore/blockcode.h" "${MeldToolchain_BLOCKCODE_DIR}/color_flood.so"
          "${MeldToolchain_STDLIB_DIR}/common.meld")
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "find_package(MeldToolchain): ${f} does not exist")
  endif()
endforeach()
CMAKE
run_or_fail "$B/configure.log" "the project did not configure against $P" \
  "$CMAKE" -S "$B/src" -B "$B/build" -DCMAKE_PREFIX_PATH="$P"
run_or_fail "$B/build.log" "the project did not build" "$CMAKE" --build "$B/build"
[ -f "$B/build/neighbor_colors.so" ] || fail "meld_add_blockcode did not make neighbor_colors.so"

PKG=$(command -v pkg-config) || fail "pkg-config is not installed"
export PKG_CONFIG_PATH
PKG_CONFIG_PATH=$(dirname "$(ls "$P"/lib*/pkgconfig/meld-blockcode.pc 2>/dev/null | head -1)")
[ -f "$PKG_CONFIG_PATH/meld-blockcode.pc" ] || fail "meld-blockcode.pc was not installed"
CFLAGS=$("$PKG" --cflags meld-blockcode) || fail "pkg-config --cflags meld-blockcode"
"$PKG" --libs meld-blockcode-polling | grep -q -- "-lblockcode_polling" || fail "pkg-config --libs meld-blockcode-polling"
# shellcheck disable=SC2086
run_or_fail "$B/cc.log" "cc with pkg-config's flags" \
  cc -shared -fPIC $CFLAGS "$B/src/neighbor_colors.c" -o "$B/pkgconfig_neighbor_colors.so"

unset VSIM_CODE_PATH MELD_STDLIB
run_or_fail "$B/cmake.out" "vsim did not run the CMake-built BlockCode" \
  env VSIM_CODE_PATH="$B/build" "$P/bin/vsim" "$B/src/cross.xml" --no-progress
run_or_fail "$B/pkg.out" "vsim did not run the pkg-config-built BlockCode" \
  "$P/bin/vsim" "$B/src/cross.xml" --code "$B/pkgconfig_neighbor_colors.so" --no-progress
grep -q "block code      neighbor-colors ($B/build/neighbor_colors.so)" "$B/cmake.out" ||
  { cat "$B/cmake.out"; fail "the world did not find neighbor_colors.so on VSIM_CODE_PATH"; }
grep -Eq "#6 +\(2,2,2\) +#ffffff white" "$B/cmake.out" ||
  { cat "$B/cmake.out"; fail "the centre block does not show six neighbours (white)"; }
[ -n "$(fingerprint "$B/cmake.out")" ] && [ "$(fingerprint "$B/cmake.out")" = "$(fingerprint "$B/pkg.out")" ] ||
  fail "the two builds ran differently: $(fingerprint "$B/cmake.out") / $(fingerprint "$B/pkg.out")"
world="$P/share/meld/examples/worlds/color-flood.xml"
run_or_fail "$B/polling.out" "vsim did not run the polling BlockCode built outside" \
  "$P/bin/vsim" "$world" --code "$B/build/wave_polling.so" --no-progress
run_or_fail "$B/installed.out" "vsim did not run the installed wave_polling.so" \
  "$P/bin/vsim" "$world" --code wave_polling.so --no-progress
[ "$(fingerprint "$B/polling.out")" = "$(fingerprint "$B/installed.out")" ] ||
  fail "wave_polling built outside differs from the installed one: $(fingerprint "$B/polling.out") / $(fingerprint "$B/installed.out")"
echo "built with find_package(MeldToolchain) and with pkg-config against $P: same run, $(fingerprint "$B/cmake.out")"
