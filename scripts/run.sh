#!/usr/bin/env bash
# The main command: install what is missing, build, and start the interactive demo (arguments go to
# sph_demo; default: the dam break on the host back end). Without a display it renders headless under
# Xvfb instead and says where the picture is.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
# Only the demo (scripts/test.sh builds the rest): configure quietly (the log is shown if it fails), then the
# build's own progress.
mkdir -p build
if ! cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >build/configure.log 2>&1; then
  cat build/configure.log >&2
  exit 1
fi
echo "building sph_demo in build/ (the first build takes several minutes: about 5 on 2 cores; later ones seconds)"
cmake --build build -j"$(nproc)" --target sph_demo
if [ $# -eq 0 ]; then
  set -- --scene scenes/dam_break.json --backend host
fi
if [ -n "${DISPLAY:-}" ]; then
  exec build/sph_demo "$@"
fi
mkdir -p out
echo "no display: rendering 240 frames headless under Xvfb instead"
xvfb-run -a -s '-screen 0 1280x720x24' build/sph_demo "$@" --frames 240 --screenshot out/demo.png
echo "picture: out/demo.png (open it with any image viewer; run scripts/run.sh on a desktop for the live demo)"
