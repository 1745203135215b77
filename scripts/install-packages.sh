#!/usr/bin/env bash
# Installs the Debian packages of the toolchain that are missing (TOOLCHAIN list): nothing when all
# are there; `apt-get update` runs only when something has to be installed; sudo when not root.
# Used by setup.sh and test.sh, so that both work on a fresh Debian 12 machine (and in CI).
set -euo pipefail

PACKAGES=(
  cmake ninja-build g++ ccache
  antlr4 libantlr4-runtime-dev
  llvm-19-dev libzstd-dev
  qt6-base-dev libqt6opengl6-dev
  libboost-test-dev libpugixml-dev libeigen3-dev
  xvfb xauth libgl1-mesa-dri fonts-dejavu-core
  python3 pkg-config groff-base dpkg-dev file
)
missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$package")
  fi
done

if ((${#missing[@]})); then
  echo "packages: installing ${#missing[@]} missing packages: ${missing[*]}"
  sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "packages: not root and no sudo: install ${missing[*]} as root" >&2; exit 1; }
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "packages: all ${#PACKAGES[@]} toolchain packages are installed"
fi

