#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine for this repository, then builds it and runs the main demo:
#   1. installs the packages of the toolchain (TOOLCHAIN list) that are missing — nothing when all
#      are there; apt-get update runs only when something has to be installed; sudo when not root;
#   2. configures with the release preset and builds (2 jobs by default: JOBS=N to change);
#   3. runs the demo: compiles the Meld example gradient-tap.meld with meldc and runs it with vsim
#      on a default Blinky Blocks world (a 7x7 floor whose centre block is tapped at 1 s).
# Safe to run again: every step is idempotent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

JOBS=${JOBS:-2}
bash scripts/install-packages.sh

echo "setup: configuring and building (release preset, $JOBS jobs)"
cmake --preset release
cmake --build --preset release --parallel "$JOBS"

echo "setup: running the demo"
mkdir -p build/demo
echo "+ build/release/meldc/meldc --robots examples/meld/gradient-tap.meld -o build/demo/gradient-tap.mbc"
build/release/meldc/meldc --robots examples/meld/gradient-tap.meld -o build/demo/gradient-tap.mbc
echo "+ build/release/apps/vsim/vsim examples/worlds/meld-gradient-tap.xml --program build/demo/gradient-tap.mbc"
build/release/apps/vsim/vsim examples/worlds/meld-gradient-tap.xml --program build/demo/gradient-tap.mbc
