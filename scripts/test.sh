#!/usr/bin/env bash
# The test command: install what is missing, build, and run every test through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh -DSPH_WERROR=ON
cd build
ctest --output-on-failure -j"$(nproc)"
