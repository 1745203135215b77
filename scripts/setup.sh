#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine for this repository, then builds it and runs the main demo:
#   1. installs the packages of the toolchain (TOOLCHAIN list) that are missing — nothing when all
#      are there; apt-get update runs only when something has to be installed; sudo when not root;
#   2. configures with the release preset and builds (2 jobs by default: JOBS=N to change);
#   3. runs vsim headless on examples/worlds/color-flood.xml with the color_flood C BlockCode.
# Safe to run again: every step is idempotent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

JOBS=${JOBS:-2}
bash scripts/install-packages.sh

echo "setup: configuring and building (release preset, $JOBS jobs)"
cmake --preset release
cmake --build --preset release --parallel "$JOBS"

echo "setup: running the demo"
echo "+ build/release/apps/vsim/vsim examples/worlds/color-flood.xml --code build/release/blockcodes/color_flood.so"
build/release/apps/vsim/vsim examples/worlds/color-flood.xml --code build/release/blockcodes/color_flood.so
