#!/usr/bin/env bash
# Configures and builds (incrementally; a no-op when up to date), then runs the whole test suite.
# This is the one test command: developers run it, and CI runs it through .ci/run.
#   PRESET=debug|asan ./scripts/test.sh   other presets of CMakePresets.json (default release)
#   JOBS=N                                build and test jobs (default 2)
# Installs the missing toolchain packages first, like setup.sh.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PRESET=${PRESET:-release}
JOBS=${JOBS:-2}
# A fresh machine (CI) has none of the toolchain: install what is missing (a no-op otherwise).
bash scripts/install-packages.sh

# MELD_BUILD_TESTS=ON explicitly: a build folder configured without the tests must not pass silently.
cmake --preset "$PRESET" -DMELD_BUILD_TESTS=ON
cmake --build --preset "$PRESET" --parallel "$JOBS"
ctest --preset "$PRESET" --parallel "$JOBS" --output-on-failure
