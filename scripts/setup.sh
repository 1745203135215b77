#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine for this repository, then builds it and runs the main demo:
#   1. installs the packages of the toolchain (TOOLCHAIN list) that are missing — nothing when all
#      are there; apt-get update runs only when something has to be installed; sudo when not root;
#   2. configures with the release preset and builds (2 jobs by default: JOBS=N to change);
#   3. runs vsim headless on examples/worlds/color-flood.xml with the color_flood C BlockCode.
# Safe to run again: every step is idempotent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PACKAGES=(
  cmake ninja-build g++ ccache
  antlr4 libantlr4-runtime-dev
  llvm-19-dev libzstd-dev
  qt6-base-dev libqt6opengl6-dev
  libboost-test-dev libpugixml-dev libeigen3-dev
  xvfb xauth libgl1-mesa-dri fonts-dejavu-core
)
JOBS=${JOBS:-2}

missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$package")
  fi
done

if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} missing packages: ${missing[*]}"
  sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "setup: not root and no sudo: install ${missing[*]} as root" >&2; exit 1; }
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#PACKAGES[@]} toolchain packages are installed"
fi

echo "setup: configuring and building (release preset, $JOBS jobs)"
cmake --preset release
cmake --build --preset release --parallel "$JOBS"

echo "setup: running the demo"
echo "+ build/release/apps/vsim/vsim examples/worlds/color-flood.xml --code build/release/blockcodes/color_flood.so"
build/release/apps/vsim/vsim examples/worlds/color-flood.xml --code build/release/blockcodes/color_flood.so
