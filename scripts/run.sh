#!/usr/bin/env bash
# The main command: install what is missing, build, and run the dam break on the serial reference.
# Arguments are passed to sph_run (default: the Martin & Moyce dam break for 0.3 s simulated).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh >/dev/null
if [ $# -eq 0 ]; then
  set -- scenes/dam_break.json --out out/dam_break
fi
exec build/sph_run "$@"
