#!/usr/bin/env bash
# Builds the scene fuzz target with clang (libFuzzer, AddressSanitizer, UBSan) and runs it for a while,
# starting from the shipped scenes and the corpus here. Any finding fails (non-zero exit) and leaves the
# input that caused it in the output folder.
#
#   run_fuzz.sh SOURCE_DIR BUILD_DIR [SECONDS]     (SECONDS default 60)
# Exit 77 (CTest: skipped) when clang with libFuzzer is not installed.
set -euo pipefail
src=$1
out=$2
seconds=${3:-60}
if ! command -v clang++ >/dev/null; then echo "clang++ not found: fuzzing skipped (apt-get install clang)"; exit 77; fi
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' >"$probe/p.cpp"
if ! clang++ -fsanitize=fuzzer "$probe/p.cpp" -o "$probe/p" 2>/dev/null; then
  echo "clang++ has no libFuzzer runtime: fuzzing skipped (apt-get install libclang-rt-14-dev)"; exit 77
fi
cmake -S "$src/tests/fuzz" -B "$out/build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$out/build" -j"$(nproc)" >/dev/null
mkdir -p "$out/new_inputs" "$out/findings"
seeds=$(mktemp -d)
cp "$src"/scenes/*.json "$seeds/"
# New inputs go to new_inputs (the first folder); the checked-in corpus and the scenes only seed.
export ASAN_OPTIONS=allocator_may_return_null=0:detect_leaks=0
export UBSAN_OPTIONS=print_stacktrace=1
"$out/build/fuzz_scene_setup" "$out/new_inputs" "$src/tests/fuzz/corpus" "$seeds" \
  -dict="$src/tests/fuzz/scene.dict" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -malloc_limit_mb=512 -max_len=4096 -artifact_prefix="$out/findings/" -print_final_stats=1
