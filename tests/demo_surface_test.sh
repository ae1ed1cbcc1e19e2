#!/usr/bin/env bash
# Renders the dam break headless (Xvfb + Mesa) with spheres and with the screen-space surface
# (--render surface) at the same frame and checks the surface's picture: water drawn where the column
# stands, nothing where the water cannot have reached yet, and a smooth surface: within the column, far
# fewer brightness steps (sphere outlines) than the spheres show. Exit 77 (skipped) without xvfb-run.
set -u
demo=$1 checker=$2 scenes=$3 out=$4
command -v xvfb-run >/dev/null || { echo "SKIP: xvfb-run not installed"; exit 77; }
mkdir -p "$out"
for render in spheres surface; do
  rm -f "$out/$render.png"
  xvfb-run -a -s '-screen 0 1280x720x24' "$demo" --scene "$scenes/dam_break.json" --backend host \
    --frames 40 --screenshot "$out/$render.png" --colour fluid --render "$render" | grep draw_ms \
    || { echo "sph_demo --render $render failed"; exit 1; }
  [ -s "$out/$render.png" ] || { echo "no screenshot written ($render)"; exit 1; }
done
# Inside the column, right of the panel: all water.
"$checker" "$out/surface.png" 0.30 0.52 0.34 0.66 0.90 1.00 drawn || exit 1
# The far end of the tank, which the surge reaches only after about 0.3 s.
"$checker" "$out/surface.png" 0.55 0.40 0.68 0.62 0.00 0.002 drawn || exit 1
# Brightness steps inside the column: the spheres' outlines against the surface's.
share() { "$checker" "$1" 0.30 0.52 0.34 0.66 0 1 edges | sed -n 's/.*(\([0-9.]*\)%).*/\1/p'; }
spheres=$(share "$out/spheres.png") surface=$(share "$out/surface.png")
echo "brightness steps inside the column: spheres $spheres%, surface $surface%"
awk -v s="$spheres" -v f="$surface" 'BEGIN { exit !(s > 5 && f < 0.25 * s) }' \
  || { echo "the surface is not smoother than the spheres (asked: under a quarter of their steps)"; exit 1; }
