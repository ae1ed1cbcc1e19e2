#!/usr/bin/env bash
# One command for every measured figure: speed (sph_bench), the integrator tables (sph_oscillators),
# validation against experiments (validate.py), stability, clustering and accuracy-against-cost studies and
# their charts (studies.py). About 35 to 40 minutes on a 2-core machine (the sum of its parts' times: the
# validation's SPHERIC 2 and wave-maker runs take about 9 and 12 minutes); --quick runs everything small in
# about 2 minutes (validate.py --quick alone took 64 s). Results in out/results/ (or the folder given with --out).
set -euo pipefail
cd "$(dirname "$0")/.."
quick=""
out=out/results
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick="--quick"; shift ;;
    --out) out="$2"; shift 2 ;;
    *) echo "usage: benchmarks/reproduce_all.sh [--quick] [--out DIR]" >&2; exit 1 ;;
  esac
done
build=${SPH_BUILD_DIR:-build}
for exe in sph_run sph_bench sph_oscillators; do
  [ -x "$build/$exe" ] || { echo "error: $build/$exe not found: build first (scripts/build.sh)" >&2; exit 1; }
done
mkdir -p "$out"
start=$(date +%s)
step() { echo; echo "== [$(( $(date +%s) - start )) s] $*"; }
step "1/4 speed: sph_bench $quick"
"$build/sph_bench" $quick --out "$out/bench"
step "2/4 integrators on the thesis's oscillators"
"$build/sph_oscillators" --out "$out/oscillators"
step "3/4 validation against experiments"
/usr/bin/python3 benchmarks/validate.py $quick --build "$build" --out "$out/validation"
step "4/4 stability map, tensile clustering, accuracy against cost, charts"
/usr/bin/python3 benchmarks/studies.py $quick --build "$build" --out "$out/studies" --bench "$out/bench/bench.csv"
step "done: results in $out/"
