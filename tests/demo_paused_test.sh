#!/usr/bin/env bash
# The paused demo sleeps until an input event (at most 0.1 s) instead of redrawing as fast as it can (it
# spun at about 1,300 frames per second, issue 10). Pauses at the first frame (--keys " ") and renders 20
# frames under Xvfb: the frame rate must stay near 10 per second, and no simulated time may pass.
# Exit 77 (skipped) when xvfb-run is missing.
set -u
demo=$1 scene=$2
command -v xvfb-run >/dev/null || { echo "SKIP: xvfb-run not installed"; exit 77; }
out=$(xvfb-run -a -s '-screen 0 1280x720x24' "$demo" --scene "$scene" --backend cpu --frames 20 --keys " ") ||
  { echo "sph_demo failed"; exit 1; }
echo "$out"
fps=$(awk '/^fps:/ { print $2 }' <<<"$out")
t=$(awk '/^simulated_time:/ { print $2 }' <<<"$out")
[ -n "$fps" ] && [ -n "$t" ] || { echo "FAILED: no fps or simulated_time in the output"; exit 1; }
# 10 frames per second when every paused frame waits 0.1 s; 30 leaves room for early wake-ups.
awk -v f="$fps" 'BEGIN { exit !(f < 30) }' || { echo "FAILED: paused at $fps frames per second (expected about 10)"; exit 1; }
awk -v t="$t" 'BEGIN { exit !(t == 0) }' || { echo "FAILED: simulated time $t s passed while paused"; exit 1; }
echo "paused: $fps frames per second"
