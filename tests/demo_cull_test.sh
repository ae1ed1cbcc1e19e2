#!/usr/bin/env bash
# Replays a 250k-particle dam-break frame headless (Xvfb + Mesa) with hidden-particle culling (--cull auto,
# src/render/occlusion_cull.h) and without it (--cull off), and checks that culling draws far fewer
# particles and the same picture: where the column stands, every pixel drawn in one is within a pixel of one
# drawn in the other (at most 2% not). Exit 77 (skipped) without xvfb-run.
set -u
run=$1 demo=$2 checker=$3 scenes=$4 out=$5
command -v xvfb-run >/dev/null || { echo "SKIP: xvfb-run not installed"; exit 77; }
rm -rf "$out" && mkdir -p "$out"
"$run" "$scenes/dam_break.json" -b host --set resolution.particles_across=50 -n 1 --frames-every 1e-7 -q \
  -o "$out/recording" > /dev/null || { echo "sph_run failed"; exit 1; }
drawn() { sed -n 's/^drawn_particles: //p' "$out/$1.txt"; }
for cull in auto off; do
  xvfb-run -a -s '-screen 0 960x540x24' "$demo" --scene "$scenes/dam_break.json" --replay "$out/recording" \
    --width 960 --height 540 --frames 3 --colour fluid --cull "$cull" --screenshot "$out/$cull.png" > "$out/$cull.txt" \
    || { echo "sph_demo --cull $cull failed"; exit 1; }
  echo "--cull $cull: $(drawn "$cull") particles drawn, $(sed -n 's/^draw_ms_per_frame: //p' "$out/$cull.txt") ms a frame"
done
all=$(sed -n 's/^particles: //p' "$out/off.txt")
[ "$(drawn off)" = "$all" ] || { echo "--cull off drew $(drawn off) of $all particles"; exit 1; }
[ "$(drawn auto)" -lt $((all / 4)) ] || { echo "--cull auto drew $(drawn auto) of $all particles (asked: under a quarter)"; exit 1; }
# The column, below the panel (whose text differs): water in both, the same outline.
"$checker" "$out/auto.png" 0.30 0.52 0.34 0.66 0.90 1.00 drawn || exit 1
"$checker" --silhouette "$out/auto.png" "$out/off.png" 0.27 0.52 0.40 0.72 0.02 || exit 1
