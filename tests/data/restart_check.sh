#!/usr/bin/env bash
# sph_run --restart end to end: a small dam break writes frames; continuing it from frame 5 (on each back end
# given) must write frames 6, 7, ... with the very same bytes as the uninterrupted run; a truncated or
# missing frame is refused with exit status 1 and a message naming the file; continued in the same folder,
# metrics.csv holds the same rows as the uninterrupted run.
#
#   restart_check.sh SPH_RUN SCENES_DIR OUT_DIR BACKEND...
set -u
run=$1 scenes=$2 out=$3
shift 3
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$out" && mkdir -p "$out" || fail "cannot create $out"
common=("$scenes/dam_break.json" --set resolution.particles_across=8 --steps 60 --frames-every 0.001 --quiet)

"$run" "${common[@]}" --out "$out/whole" > /dev/null || fail "the uninterrupted run failed"
[ -f "$out/whole/frame_00016.ply" ] || fail "the uninterrupted run wrote no frame 16"
ls "$out/whole" | grep -q '\.tmp$' && fail "temporary frame files were left behind"

for backend in "$@"; do
  "$run" "${common[@]}" --backend "$backend" --restart "$out/whole/frame_00005.ply" --out "$out/$backend" > "$out/$backend.txt" ||
    fail "the run continued on $backend failed"
  grep -q "restart: .*frame 5, step" "$out/$backend.txt" || fail "the summary does not say where the run continued"
  [ -e "$out/$backend/frame_00005.ply" ] && fail "the continued run rewrote the frame it started from"
  [ -f "$out/$backend/frame_00006.ply" ] || fail "the continued run does not number its frames on from 6"
  for f in "$out/$backend"/frame_*.ply; do
    cmp -s "$f" "$out/whole/$(basename "$f")" || fail "$backend: $(basename "$f") differs from the uninterrupted run"
  done
  [ "$(ls "$out/$backend"/frame_*.ply | wc -l)" -eq 11 ] || fail "$backend: expected frames 6 to 16"
done

# Continued in the folder of an interrupted run: metrics.csv keeps the rows up to the frame's step and the
# continuation appends the same rows as the uninterrupted run (all columns but the wall time).
cp -r "$out/whole" "$out/same"
"$run" "${common[@]}" --restart "$out/same/frame_00005.ply" --out "$out/same" > /dev/null || fail "continuing in place failed"
cut -d, -f1-11 "$out/whole/metrics.csv" > "$out/whole_metrics.txt"
cut -d, -f1-11 "$out/same/metrics.csv" > "$out/same_metrics.txt"
cmp -s "$out/whole_metrics.txt" "$out/same_metrics.txt" ||
  fail "metrics.csv of the run continued in place differs from the uninterrupted one: $(diff "$out/whole_metrics.txt" "$out/same_metrics.txt" | head -5)"

# A folder holding another run's metrics.csv is refused (its rows would be spliced with this run's), and
# so is an end (--steps) the frame has already passed; both leave the folder as it was.
mkdir -p "$out/other"
"$run" "$scenes/hydrostatic_tank.json" --set resolution.particles_across=6 --steps 30 --quiet --out "$out/other" > /dev/null ||
  fail "the other run failed"
cp "$out/other/metrics.csv" "$out/other_metrics_before.csv"
"$run" "${common[@]}" --restart "$out/whole/frame_00005.ply" --out "$out/other" > /dev/null 2> "$out/other.txt"
status=$?
[ "$status" -eq 1 ] || fail "continuing into another run's folder exited with $status, expected 1"
grep -q "belongs to another run" "$out/other.txt" || fail "no 'belongs to another run' message: $(cat "$out/other.txt")"
cmp -s "$out/other/metrics.csv" "$out/other_metrics_before.csv" || fail "the other run's metrics.csv was changed"
"$run" "$scenes/dam_break.json" --set resolution.particles_across=8 --steps 3 --quiet --restart "$out/whole/frame_00005.ply" \
  --out "$out/past" > /dev/null 2> "$out/past.txt"
status=$?
[ "$status" -eq 1 ] || fail "--steps before the frame's step exited with $status, expected 1"
grep -q "already past the end" "$out/past.txt" || fail "no 'already past the end' message: $(cat "$out/past.txt")"

head -c 3000 "$out/whole/frame_00005.ply" > "$out/truncated.ply"
for bad in "$out/truncated.ply" "$out/no_such_frame.ply"; do
  "$run" "${common[@]}" --restart "$bad" --out "$out/bad" > /dev/null 2> "$out/bad.txt"
  status=$?
  [ "$status" -eq 1 ] || fail "--restart $bad exited with $status, expected 1"
  grep -qF "$bad" "$out/bad.txt" || fail "the refusal of $bad does not name it: $(cat "$out/bad.txt")"
done
echo "restart: frames 6 to 16 identical on: $*"
