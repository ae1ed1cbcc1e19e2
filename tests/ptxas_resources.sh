#!/bin/bash
# ptxas_resources: compiles the cuda back end's device source (src/cuda/device_backend_cuda.cu) for sm_90
# with -Xptxas -v and checks what every kernel that runs the project's per-particle code (the functors
# named sph::cuda_device::*Fn, in Thrust's and CUB's kernels) costs each thread: registers, stack frame,
# spilled bytes (issue 11, Build item 1). A stack frame or a spill is local memory, per thread, on every
# particle; more registers mean fewer threads resident per SM.
#
# usage: ptxas_resources.sh NVCC SOURCE_DIR WORK_DIR "LIMITS" [extra nvcc flags...]
#   LIMITS: space-separated FUNCTOR:REGISTERS:STACK:SPILL (bytes), "*" for every functor not named;
#           ptxas's figures must not exceed them.
# Exit status: 0 all within limits, 1 a limit exceeded (or nvcc failed, or an expected kernel is
# missing), 77 (skipped) where nvcc is not found.
set -u
nvcc=$1 source_dir=$2 work=$3 limits=$4
shift 4
if [ -z "$nvcc" ] || ! command -v "$nvcc" >/dev/null 2>&1; then
  echo "nvcc not found: ptxas_resources skipped"
  exit 77
fi
mkdir -p "$work"
log=$work/ptxas.txt
if ! "$nvcc" -std=c++17 -O3 -DNDEBUG --extended-lambda --expt-relaxed-constexpr -gencode arch=compute_90,code=sm_90 \
    -I"$source_dir/src" "$@" -Xptxas -v -c "$source_dir/src/cuda/device_backend_cuda.cu" \
    -o "$work/device_backend_cuda.o" >"$log" 2>&1; then
  cat "$log"
  echo "FAIL: nvcc could not compile src/cuda/device_backend_cuda.cu"
  exit 1
fi

# ptxas prints, per entry function:
#   Compiling entry function 'MANGLED' for 'sm_90'
#   Function properties for MANGLED
#       S bytes stack frame, T bytes spill stores, L bytes spill loads
#   Used R registers, ...
# The functor is read from the mangled name (11cuda_device8ForcesFnE), the kernel from the name's CUB
# kernel (for_each_index: the project's own; DeviceSelectSweepKernel: copy_if; DeviceReduce*: reduce).
awk -v limits="$limits" '
  function functor_of(name,   f) {
    if (index(name, "11cuda_device") == 0 || !match(name, /[0-9]+[A-Z][A-Za-z]*Fn[EI]/)) return ""
    f = substr(name, RSTART, RLENGTH - 1)
    sub(/^[0-9]+/, "", f)
    return f
  }
  function kernel_of(name) {
    if (match(name, /(for_each_index_bounded|for_each_index|static_kernel|DeviceSelectSweepKernel|DeviceReduceSingleTileKernel|DeviceReduceKernel|DeviceScanKernel|transform_kernel)/))
      return substr(name, RSTART, RLENGTH)
    return "kernel"
  }
  BEGIN {
    n = split(limits, items, " ")
    for (i = 1; i <= n; ++i) {
      split(items[i], f, ":")
      max_regs[f[1]] = f[2]; max_stack[f[1]] = f[3]; max_spill[f[1]] = f[4]
    }
    bad = 0
    printf "%-16s %-30s %9s %7s %13s  %s\n", "functor", "kernel", "registers", "stack", "spill st/ld", "limits (registers stack spill)"
  }
  /Compiling entry function/ {
    match($0, /\047[^\047]+\047/)
    current = substr($0, RSTART + 1, RLENGTH - 2)
    stack = -1
    next
  }
  /Function properties for/ {
    props = ($NF == current)
    next
  }
  /bytes stack frame/ {
    if (props) { stack = $1; stores = $5; loads = $9 }
    props = 0
    next
  }
  /Used [0-9]+ registers/ {
    fn = functor_of(current)
    if (fn == "") next
    match($0, /Used [0-9]+ registers/)
    regs = substr($0, RSTART + 5, RLENGTH - 15) + 0
    key = (fn in max_regs) ? fn : "*"
    seen[fn] = 1
    verdict = "ok"
    if (stack < 0) verdict = "FAIL (no stack figures)"
    else if (regs > max_regs[key] || stack > max_stack[key] || stores > max_spill[key] || loads > max_spill[key]) verdict = "FAIL"
    if (verdict != "ok") bad = 1
    printf "%-16s %-30s %9d %7d %6d/%-6d  %d %d %d  %s\n", fn, kernel_of(current), regs, stack, stores, loads,
           max_regs[key], max_stack[key], max_spill[key], verdict
  }
  END {
    for (fn in max_regs) if (fn != "*" && !(fn in seen)) { print "FAIL: no kernel found for " fn; bad = 1 }
    exit bad
  }
' "$log"
status=$?
[ $status -eq 0 ] && echo "ptxas_resources: every per-particle kernel within its limits" || echo "ptxas_resources: FAILED (full ptxas log: $log)"
exit $status
