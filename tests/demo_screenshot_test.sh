#!/usr/bin/env bash
# Renders the dam break headless (Xvfb + Mesa) on the host back end and checks the picture: fluid where the
# column must be, none where the water cannot have reached yet. Exit 77 (skipped) when xvfb-run is missing.
set -u
demo=$1 checker=$2 scenes=$3 out=$4
command -v xvfb-run >/dev/null || { echo "SKIP: xvfb-run not installed"; exit 77; }
rm -f "$out"
xvfb-run -a -s '-screen 0 1280x720x24' "$demo" --scene "$scenes/dam_break.json" --backend host \
  --frames 40 --screenshot "$out" --colour fluid || { echo "sph_demo failed"; exit 1; }
[ -s "$out" ] || { echo "no screenshot written"; exit 1; }
# The column at the left wall of the tank, right of the panel.
"$checker" "$out" 0.28 0.45 0.40 0.70 0.30 1.00 || exit 1
# The far end of the tank, which the surge reaches only after about 0.3 s.
"$checker" "$out" 0.55 0.40 0.68 0.62 0.00 0.002 || exit 1
