#!/usr/bin/env bash
# One command that checks the cuda back end on a GPU (issue 11, item 8), in two halves:
#
#   scripts/gpu_check.sh --prepare [--bundle DIR]
#       Here, where nvcc is (no GPU needed): builds for sm_90 only, CUDA runtime linked statically,
#         DIR/bin/default  the default Release build: sph_run, sph_bench, sph_device_tests, sph_interop_probe
#         DIR/bin/bitwise  the --fmad=false build (SPH_CUDA_FMAD=OFF): sph_run, sph_device_tests, which
#                          give host's bits on cuda and assert it
#       and collects the scenes, the test data, the OpenMP runtime (DIR/lib) and the EGL loader (glvnd's
#       libEGL.so.1 and libGLdispatch.so.0, DIR/egl, used only where the machine has none) beside them.
#       Checks with ldd that nothing else is missing on a machine with a driver but no Debian packages,
#       and that DIR stays under 64 MiB. Build trees go to DIR.build (not needed there). DIR: out/gpu_check.
#
#   scripts/gpu_check.sh --run [--bundle DIR] [--results RES]
#       There, on the GPU machine (repository and DIR carried), in under 8 minutes, each step with its own
#       time limit: the GPU's facts (nvidia-smi); the device tests on cuda, bitwise build; host-against-cuda
#       byte comparison (cmp) of the PLY frames of the bitwise sph_run on the dam break (penalty and mirror
#       walls), the water jet at low resolution past 0.85 s (it reaches the absorbing ground), obstacles,
#       viscosity_cubes and drop_zero_g with XSPH; compute-sanitizer memcheck on a short run when present;
#       sph_bench on cuda at about 16k, 100k, 1M and 4M particles; CUDA-OpenGL interop in a headless EGL
#       context (sph_interop_probe: the cuda back end writes vertex buffers, read back and compared with
#       the host path); last, the device tests on cuda's default build. Writes RES/summary.txt (pass/fail table and figures), RES/steps.log and RES/bench.csv
#       (RES: DIR/results).
#       Without a GPU every GPU step reports "skipped: no GPU". Exit status 1 when a step failed, 2 when
#       none failed but the time budget (GPU_CHECK_SECONDS, 450) left some not run, else 0.
#
# The demo is not in the bundle: it needs Debian's GLFW (X11 only in 3.3), GLEW, libGL, Dear ImGui and the
# X11 client libraries (ldd), and an X server; a bare GPU machine has none of them. sph_interop_probe
# stands in: the demo's interop path (the back end's write_gl_buffers) in an EGL context, no display.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
MODE=""
BUNDLE="$ROOT/out/gpu_check"
RES=""
while [ $# -gt 0 ]; do
  case "$1" in
    --prepare|--run) MODE="${1#--}" ;;
    --bundle) BUNDLE="$(realpath -m "${2:?--bundle needs a folder}")"; shift ;;
    --results) RES="$(realpath -m "${2:?--results needs a folder}")"; shift ;;
    -h|--help) sed -n '2,29p' "$0"; exit 0 ;;
    *) echo "gpu_check.sh: unknown argument '$1'; use --prepare or --run [--bundle DIR] [--results RES]" >&2; exit 1 ;;
  esac
  shift
done
[ -n "$MODE" ] || { echo "gpu_check.sh: say --prepare (here) or --run (on the GPU machine); --help explains" >&2; exit 1; }

# ---------------------------------------------------------------------------------------------- prepare
prepare() {
  command -v nvcc >/dev/null || [ -x /usr/local/cuda/bin/nvcc ] || { echo "gpu_check.sh --prepare: nvcc not found (CUDA toolkit in /usr/local/cuda)" >&2; exit 1; }
  export PATH="$PATH:/usr/local/cuda/bin"
  local jobs="${GPU_CHECK_JOBS:-2}"
  rm -rf "$BUNDLE" && mkdir -p "$BUNDLE.build"  "$BUNDLE/bin" "$BUNDLE/lib" "$BUNDLE/src/tests" || exit 1
  local kind fmad targets
  for kind in bitwise default; do
    if [ $kind = bitwise ]; then fmad=OFF; targets="sph_run sph_device_tests"; else fmad=ON; targets="sph_run sph_bench sph_device_tests sph_interop_probe"; fi
    echo "== building the $kind build (sm_90, SPH_CUDA_FMAD=$fmad): $targets"
    cmake -S "$ROOT" -B "$BUNDLE.build/$kind" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
          -DCMAKE_CUDA_RUNTIME_LIBRARY=Static -DSPH_CUDA_FMAD=$fmad -DSPH_ENABLE_CUDA=ON -DSPH_WITH_OPENVDB=OFF >"$BUNDLE.build/$kind.configure.log" 2>&1 \
      || { tail -20 "$BUNDLE.build/$kind.configure.log"; echo "gpu_check.sh: configure failed ($kind)" >&2; exit 1; }
    grep -q '^CMAKE_CUDA_COMPILER:.*nvcc' "$BUNDLE.build/$kind/CMakeCache.txt" \
      || { echo "gpu_check.sh: cmake did not take nvcc ($kind); see $BUNDLE.build/$kind.configure.log" >&2; exit 1; }
    # shellcheck disable=SC2086
    nice cmake --build "$BUNDLE.build/$kind" -j"$jobs" --target $targets || { echo "gpu_check.sh: build failed ($kind)" >&2; exit 1; }
    mkdir -p "$BUNDLE/bin/$kind"
    for t in $targets; do
      local f; f="$(find "$BUNDLE.build/$kind" -name "$t" -type f -perm -u+x | head -1)"
      [ -n "$f" ] || { echo "gpu_check.sh: $t not built ($kind)" >&2; exit 1; }
      cp "$f" "$BUNDLE/bin/$kind/" && strip "$BUNDLE/bin/$kind/$t"
    done
  done
  # The executables read scenes and test data from the source folder compiled into them (SPH_SOURCE_DIR);
  # --run points that path at this copy.
  cp -r "$ROOT/scenes" "$BUNDLE/src/" && cp -r "$ROOT/tests/data" "$BUNDLE/src/tests/" || exit 1
  echo "$ROOT" >"$BUNDLE/source_dir.txt"
  # Libraries: the C and C++ runtimes come with any Linux that has nvcc's host compiler; the OpenMP
  # runtime may not, so it travels. Anything else is a failure here, not there.
  local lib missing=0 f
  lib="$(g++ -print-file-name=libgomp.so.1)"
  cp -L "$lib" "$BUNDLE/lib/" || exit 1
  # The probe opens libEGL.so.1 at run time (dlopen): glvnd's vendor-neutral loader, which finds the
  # NVIDIA driver's EGL through its vendor file. Kept apart from DIR/lib: used only where the machine has none.
  mkdir -p "$BUNDLE/egl" || exit 1
  for lib in libEGL.so.1 libGLdispatch.so.0; do
    f="$(ldconfig -p | awk -v n="$lib" '$1 == n && /x86-64/ {print $NF; exit}')"
    [ -n "$f" ] && cp -L "$f" "$BUNDLE/egl/" || { echo "gpu_check.sh: $lib not found here (Debian: libegl1, libglvnd0)" >&2; exit 1; }
  done
  : >"$BUNDLE/ldd.txt"
  for f in "$BUNDLE"/bin/*/*; do
    echo "$f:" >>"$BUNDLE/ldd.txt"
    ldd "$f" >>"$BUNDLE/ldd.txt" 2>&1
    while read -r name _; do
      case "$name" in
        linux-vdso.so.*|/lib64/ld-linux*|ld-linux*|libc.so.*|libm.so.*|libstdc++.so.*|libgcc_s.so.*|libpthread.so.*|libdl.so.*|librt.so.*|libgomp.so.*) ;;
        *) echo "gpu_check.sh: $f needs $name, which a bare GPU machine may lack" >&2; missing=1 ;;
      esac
    done < <(ldd "$f" | awk '{print $1}')
  done
  [ $missing = 0 ] || exit 1
  objdump -T "$BUNDLE"/bin/*/* 2>/dev/null | grep -o 'GLIBC_[0-9.]*\|GLIBCXX_[0-9.]*' | sort -Vu | tail -n 40 \
    | awk '/GLIBC_/{c=$0} /GLIBCXX_/{x=$0} END{print "needs at least " c " and " x}' >"$BUNDLE/needs.txt"
  local size; size="$(du -sm "$BUNDLE" | cut -f1)"
  echo "== bundle $BUNDLE: ${size} MiB; $(cat "$BUNDLE/needs.txt"); libraries (ldd): $(awk '/=>/{print $1}' "$BUNDLE/ldd.txt" | sort -u | tr '\n' ' ')"
  [ "$size" -lt 64 ] || { echo "gpu_check.sh: the bundle is ${size} MiB, over the 64 MiB that may travel" >&2; exit 1; }
  echo "== carry it to the GPU machine with the repository and run: scripts/gpu_check.sh --run"
}

# -------------------------------------------------------------------------------------------------- run
ROWS=()
FAILED=0
INCOMPLETE=0
LOG=""
# The whole run stays inside 8 minutes: each step's limit is cut to what is left of GPU_CHECK_SECONDS.
DEADLINE=$((EPOCHSECONDS + ${GPU_CHECK_SECONDS:-450}))
# step NAME SECONDS COMMAND...: runs COMMAND under a time limit, its output into the log; exit 77 = skipped.
step() {
  local name="$1" limit="$2"; shift 2
  local t0 rc note left=$((DEADLINE - EPOCHSECONDS))
  if [ $left -lt 10 ]; then
    ROWS+=("$(printf '%-44s %-9s %s' "$name" "-" "NOT RUN: the time budget is spent")"); INCOMPLETE=1; return
  fi
  local cut=0
  [ "$limit" -le $left ] || { limit=$left; cut=1; }
  t0=$EPOCHREALTIME
  local from; from=$(($(wc -l <"$LOG") + 1))
  { echo; echo "==== $name ($(date -u +%T), limit ${limit}s): $*"; } >>"$LOG"
  if declare -F "$1" >/dev/null; then  # a function of this script: timeout needs a program
    timeout -k 10 "$limit" bash -c '"$@"' gpu_check "$@" >>"$LOG" 2>&1
  else
    timeout -k 10 "$limit" "$@" >>"$LOG" 2>&1
  fi
  rc=$?
  local secs; secs=$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN{printf "%.1f", b - a}')
  case $rc in
    0) note="pass$(tail -n +"$from" "$LOG" | grep -a '^RESULT: ' | tail -1 | cut -c9- | sed 's/^./: &/')" ;;
    77) note="skipped: $(grep -a '^SKIP' "$LOG" | tail -1 | cut -c7-)" ;;
    124|137) if ((cut)); then note="NOT FINISHED: the time budget ran out after ${limit}s"; INCOMPLETE=1
             else note="FAIL: over ${limit}s"; FAILED=1; fi ;;
    *) note="FAIL: exit $rc: $(tail -n +"$from" "$LOG" | grep -av '^====' | tail -1 | cut -c1-100)"; FAILED=1 ;;
  esac
  echo "==== $name: $note (${secs}s)" >>"$LOG"
  ROWS+=("$(printf '%-44s %-9s %s' "$name" "${secs}s" "$note")")
}
skip() { ROWS+=("$(printf '%-44s %-9s %s' "$1" "-" "skipped: $2")"); echo "==== $1: skipped: $2" >>"$LOG"; }

# frames_match NAME SCENE ARGS...: the same run on host and cuda (bitwise build), every PLY frame equal.
frames_match() {
  local name="$1" scene="$2"; shift 2
  local dir="$WORK/frames/$name" b
  rm -rf "$dir"
  for b in host cuda; do
    OMP_NUM_THREADS="$(nproc)" "$BUNDLE/bin/bitwise/sph_run" "$SRC/scenes/$scene" --backend $b --quiet --out "$dir/$b" "$@" || return 1
  done
  local n=0 f
  for f in "$dir"/host/frame_*.ply; do
    [ -f "$f" ] || { echo "no frames written"; return 1; }
    cmp "$f" "$dir/cuda/$(basename "$f")" || return 1
    n=$((n + 1))
  done
  [ "$(ls "$dir"/cuda/frame_*.ply | wc -l)" = "$n" ] || { echo "cuda wrote another number of frames"; return 1; }
  echo "RESULT: $n frames byte-identical"
}

# The interop probe with an EGL loader and the NVIDIA EGL vendor file, where the machine lacks them.
interop_probe() {
  local egl="" f
  ldconfig -p 2>/dev/null | grep -q 'libEGL\.so\.1 ' || egl="$BUNDLE/egl:"
  [ -d /usr/local/nvidia/lib64 ] && egl="$egl/usr/local/nvidia/lib64:"
  if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then
    for f in /usr/share/glvnd/egl_vendor.d/10_nvidia.json /etc/glvnd/egl_vendor.d/10_nvidia.json \
             /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json; do
      [ -f "$f" ] && { export __EGL_VENDOR_LIBRARY_FILENAMES="$f"; break; }
    done
  fi
  echo "EGL loader path: ${egl:-(the system one)}; vendor file: ${__EGL_VENDOR_LIBRARY_FILENAMES:-(searched by glvnd)}"
  LD_LIBRARY_PATH="$egl$LD_LIBRARY_PATH" "$BUNDLE/bin/default/sph_interop_probe" 80  # also timed at about 1M
}

memcheck() {
  local out
  out="$(compute-sanitizer --tool memcheck --error-exitcode 9 "$BUNDLE/bin/default/sph_run" "$SRC/scenes/dam_break.json" \
           --backend cuda --steps 20 --quiet --set resolution.particles_across=10 --out "$WORK/memcheck" 2>&1)"
  local rc=$?
  echo "$out"
  if [ $rc != 0 ] && grep -q "Device not supported" <<<"$out"; then echo "SKIP: compute-sanitizer does not support this device here"; return 77; fi
  return $rc
}

run() {
  [ -x "$BUNDLE/bin/bitwise/sph_run" ] && [ -x "$BUNDLE/bin/default/sph_bench" ] \
    || { echo "gpu_check.sh --run: no bundle in $BUNDLE; run --prepare first (where nvcc is) and carry it" >&2; exit 1; }
  RES="${RES:-$BUNDLE/results}"
  WORK="$(mktemp -d /tmp/gpu_check.XXXXXX)"
  mkdir -p "$RES" || exit 1
  LOG="$RES/steps.log"; : >"$LOG"; rm -f "$RES/bench.csv" "$RES/summary.txt"
  export LD_LIBRARY_PATH="$BUNDLE/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  # The executables look for scenes and test data under the source folder they were built from.
  SRC="$(cat "$BUNDLE/source_dir.txt")"
  if [ ! -d "$SRC/scenes" ]; then
    mkdir -p "$(dirname "$SRC")" 2>/dev/null && ln -sfn "$BUNDLE/src" "$SRC" 2>/dev/null \
      || { echo "gpu_check.sh: cannot make $SRC point at $BUNDLE/src (the built-in scene path)" >&2; exit 1; }
  fi
  export -f frames_match memcheck interop_probe
  export WORK SRC BUNDLE
  local gpu=0 facts="none"
  if command -v nvidia-smi >/dev/null && nvidia-smi -L 2>/dev/null | grep -q '^GPU'; then
    gpu=1
    facts="$(nvidia-smi --query-gpu=name,compute_cap,memory.total,driver_version,clocks.max.sm --format=csv,noheader 2>&1 | head -1)"
    step "GPU facts (nvidia-smi)" 30 nvidia-smi
  else
    skip "GPU facts (nvidia-smi)" "no GPU"
  fi
  step "bundle libraries present (ldd)" 30 bash -c "! ldd '$BUNDLE'/bin/*/* | grep 'not found'"
  if [ $gpu = 1 ]; then
    step "device tests, cuda, bitwise (--fmad=false)" 150 env SPH_DEVICE_BACKEND=cuda "$BUNDLE/bin/bitwise/sph_device_tests"
    step "frames host = cuda: dam break, penalty walls" 60 frames_match dam_penalty dam_break.json --time 0.05 --frames-every 0.01
    step "frames host = cuda: dam break, mirror walls" 60 frames_match dam_mirror dam_break.json --time 0.05 --frames-every 0.01 --set sph.walls=mirror
    step "frames host = cuda: water jet to the ground" 90 frames_match water_jet water_jet.json --time 1.0 --frames-every 0.1 --set resolution.particles_across=6
    step "frames host = cuda: obstacles" 60 frames_match obstacles obstacles.json --time 0.1 --frames-every 0.02
    step "frames host = cuda: viscosity_cubes" 60 frames_match viscosity_cubes viscosity_cubes.json --time 0.1 --frames-every 0.02
    step "frames host = cuda: drop_zero_g with XSPH" 60 frames_match drop_xsph drop_zero_g.json --time 0.1 --frames-every 0.02 --set fluids.0.xsph=0.1
    step "frames host = cuda: dam break, DFSPH" 60 frames_match dam_dfsph dam_break.json --time 0.05 --frames-every 0.01 --set solver=dfsph
    step "frames host = cuda: dam break, boundary particles" 60 frames_match dam_particles dam_break.json --time 0.05 --frames-every 0.01 --set sph.walls=particles
    step "frames host = cuda: cup mesh, DFSPH" 60 frames_match mesh_dfsph mesh_obstacle.json --time 0.05 --frames-every 0.01 --set solver=dfsph
    step "frames host = cuda: tank, PBF at 4 ms" 60 frames_match tank_pbf hydrostatic_tank.json --time 0.2 --frames-every 0.04 \
         --set solver=pbf --set time_step.mode=fixed --set time_step.dt=0.004
    step "frames host = cuda: two layers (ratio 10), DFSPH" 60 frames_match layers_dfsph two_layers.json --time 0.05 --frames-every 0.01 \
         --set solver=dfsph
    step "frames host = cuda: drop with surface tension" 60 frames_match drop_sigma drop_oscillation.json --time 0.05 --frames-every 0.01
    step "frames host = cuda: drop under WCSPH, cubic spline kernel" 60 frames_match drop_cubic drop_oscillation.json --time 0.05 \
         --frames-every 0.01 --set solver=wcsph --set sph.kernel=cubic_spline
    step "frames host = cuda: jelly springs and water" 60 frames_match jelly viscoelastic.json --time 0.15 --frames-every 0.03 \
         --set fluids.0.spring_plasticity=2 --set fluids.0.spring_yield=0.02
    step "frames host = cuda: jelly springs under DFSPH" 60 frames_match jelly_dfsph viscoelastic.json --time 0.15 --frames-every 0.03 \
         --set fluids.0.spring_plasticity=2 --set fluids.0.spring_yield=0.02 --set solver=dfsph
    step "frames host = cuda: jelly springs under PBF" 60 frames_match jelly_pbf viscoelastic.json --time 0.05 --frames-every 0.01 \
         --set fluids.0.spring_plasticity=2 --set fluids.0.spring_yield=0.02 --set solver=pbf
    step "frames host = cuda: two layers (ratio 10), PBF" 60 frames_match layers_pbf two_layers.json --time 0.05 --frames-every 0.01 \
         --set solver=pbf
    step "frames host = cuda: two layers, PBF with the artificial viscosity" 60 frames_match layers_pbf_av two_layers.json \
         --time 0.05 --frames-every 0.01 --set solver=pbf --set pbf.artificial_viscosity=true
    step "frames host = cuda: drop, PBF with the continuum surface force" 60 frames_match drop_pbf drop_oscillation.json --time 0.05 \
         --frames-every 0.01 --set solver=pbf --set pbf.xsph=0.1
    step "frames host = cuda: contact angles (sheared images)" 60 frames_match contact contact_angle.json --time 0.05 --frames-every 0.01
    step "frames host = cuda: compound drop (interface tension, csf)" 60 frames_match compound compound_drop.json --time 0.05 \
         --frames-every 0.01 --set resolution.spacing=0.006
    if command -v compute-sanitizer >/dev/null; then
      step "compute-sanitizer memcheck (20 steps)" 90 memcheck
    else
      skip "compute-sanitizer memcheck (20 steps)" "compute-sanitizer not found"
    fi
    step "sph_bench cuda: dam break 16k, 100k, 1M, 4M" 240 "$BUNDLE/bin/default/sph_bench" --backends cuda --scenes "$SRC/scenes" \
         --dam-sizes 20 37 80 --dam-cuda 127 --workload dam_break_20 --workload dam_break_37 --workload dam_break_80 \
         --workload dam_break_127 --workload solver_wcsph --workload solver_dfsph --workload solver_pbf --workload solver_pbf_coarse \
         --workload walls_mirror --workload walls_particles --out "$WORK/bench"
    cp "$WORK/bench/bench.csv" "$RES/" 2>/dev/null
    step "interop probe: cuda writes GL buffers (EGL)" 90 interop_probe
    # Last: nvcc's default fused multiply-adds against the rounding tolerance (tests/device_compare.h).
    step "device tests, cuda, default build (rounding reach)" 150 env SPH_DEVICE_BACKEND=cuda "$BUNDLE/bin/default/sph_device_tests"
  else
    local s
    for s in "device tests, cuda, bitwise (--fmad=false)" "device tests, cuda, default build (rounding reach)" \
             "frames host = cuda (17 scenes)" "compute-sanitizer memcheck (20 steps)" "sph_bench cuda: dam break 16k, 100k, 1M, 4M" \
             "interop probe: cuda writes GL buffers (EGL)"; do
      skip "$s" "no GPU"
    done
  fi
  skip "demo with interop, headless screenshot" "sph_demo needs GLFW/GLEW/libGL/X11 and an X server; the interop probe stands in"
  {
    echo "gpu_check.sh --run, $(date -u '+%F %T') UTC, on $(hostname)"
    echo "GPU: $facts"
    echo
    printf '%-44s %-9s %s\n' "step" "time" "result"
    printf '%s\n' "${ROWS[@]}"
    echo
    if [ -f "$RES/bench.csv" ]; then
      echo "sph_bench on cuda (median ms/step; targets: 16k >= 5000 steps/s, 1M >= 1.5e9 particle-steps/s):"
      awk -F, 'NR>1 {printf "  %-16s %9d particles  %9.3f ms/step  %8.0f steps/s  %.3e particle-steps/s\n", $2, $3, $4, 1000/$4, $8}' "$RES/bench.csv"
    fi
    echo
    local verdict=PASS
    ((INCOMPLETE)) && verdict="INCOMPLETE (no failure)"
    ((gpu)) || verdict="NO GPU: nothing ran on a GPU; the bundle's checks pass"
    ((FAILED)) && verdict=FAIL
    echo "overall: $verdict (details in steps.log)"
  } >"$RES/summary.txt"
  cat "$RES/summary.txt"
  rm -rf "$WORK"
  ((FAILED)) && exit 1
  ((INCOMPLETE)) && exit 2
  exit 0
}

if [ "$MODE" = prepare ]; then prepare; else run; fi
