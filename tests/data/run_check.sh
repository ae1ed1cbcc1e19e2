#!/usr/bin/env bash
# Runs a command and checks its exit status and output; used by tests/cli_tests.cmake.
#
#   run_check.sh [checks...] -- COMMAND [ARGS...]
#
# Checks (any number, all must hold):
#   --exit N           exit status must be N ("nonzero": anything but 0)
#   --stderr TEXT      stderr contains TEXT (fixed string)
#   --stdout TEXT      stdout contains TEXT (fixed string)
#   --no-stderr TEXT   stderr does not contain TEXT (fixed string)
#   --stdout-line TEXT stdout has a line that is exactly TEXT
#   --stdout-prefix T  stdout has a line starting with T
#   --file PATH        PATH exists after the run
#   --min-lines PATH N PATH has at least N lines
#   --csv-column PATH NAME  the first line of PATH, split at commas, has a field NAME
#   --clean DIR        remove DIR before running (so old output cannot pass the file checks)
#   --max-seconds S    the command finishes within S seconds
#   --csv-complete PATH  PATH ends with a newline and every line has as many non-empty fields as its header
#   --setup CMD        run CMD with bash before the command (after --clean); it must succeed
#   --signal SIG S     send signal SIG (TERM, INT, ...) to the command S seconds after its start
set -u

expect_exit=0
declare -a checks=()
declare -a clean=()
declare -a setup=()
max_seconds=""
signal=""
signal_after=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    --exit) expect_exit="$2"; shift 2 ;;
    --stderr|--no-stderr|--stdout|--stdout-line|--stdout-prefix|--file) checks+=("$1" "$2" ""); shift 2 ;;
    --csv-complete) checks+=("$1" "$2" ""); shift 2 ;;
    --min-lines|--csv-column) checks+=("$1" "$2" "$3"); shift 3 ;;
    --clean) clean+=("$2"); shift 2 ;;
    --setup) setup+=("$2"); shift 2 ;;
    --signal) signal="$2"; signal_after="$3"; shift 3 ;;
    --max-seconds) max_seconds="$2"; shift 2 ;;
    *) echo "run_check.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
if [ $# -eq 0 ]; then echo "run_check.sh: missing -- COMMAND" >&2; exit 2; fi
shift
if [ $# -eq 0 ]; then echo "run_check.sh: missing COMMAND after --" >&2; exit 2; fi

for d in "${clean[@]+"${clean[@]}"}"; do rm -rf -- "$d"; done
for c in "${setup[@]+"${setup[@]}"}"; do
  bash -c "$c" || { echo "run_check.sh: setup command failed: $c" >&2; exit 2; }
done

work=$(mktemp -d)
trap 'rm -rf -- "$work"' EXIT
start=$(date +%s.%N)
if [ -n "$signal" ]; then
  # Job control on: a script's background job would otherwise start with SIGINT ignored.
  set -m
  "$@" >"$work/stdout" 2>"$work/stderr" &
  pid=$!
  set +m
  sleep "$signal_after"
  kill -s "$signal" "$pid" 2>/dev/null || echo "run_check.sh: the command had ended before the signal"
  wait "$pid"
  status=$?
else
  "$@" >"$work/stdout" 2>"$work/stderr"
  status=$?
fi
end=$(date +%s.%N)

failed=0
fail() { echo "FAILED: $*"; failed=1; }

echo "command: $*"
echo "exit status: $status"
echo "---- stdout ----"; cat "$work/stdout"
echo "---- stderr ----"; cat "$work/stderr"
echo "----------------"

if [ "$expect_exit" = "nonzero" ]; then
  [ "$status" -ne 0 ] || fail "expected a non-zero exit status, got 0"
else
  [ "$status" -eq "$expect_exit" ] || fail "expected exit status $expect_exit, got $status"
fi
if [ -n "$max_seconds" ]; then
  awk -v a="$start" -v b="$end" -v m="$max_seconds" 'BEGIN { exit !(b - a <= m) }' ||
    fail "took longer than $max_seconds s"
fi

i=0
while [ $i -lt ${#checks[@]} ]; do
  kind=${checks[$i]}; a=${checks[$((i + 1))]}; b=${checks[$((i + 2))]}
  i=$((i + 3))
  case "$kind" in
    --stderr) grep -qF -- "$a" "$work/stderr" || fail "stderr does not contain: $a" ;;
    --no-stderr) ! grep -qF -- "$a" "$work/stderr" || fail "stderr contains: $a" ;;
    --stdout) grep -qF -- "$a" "$work/stdout" || fail "stdout does not contain: $a" ;;
    --stdout-line) grep -qxF -- "$a" "$work/stdout" || fail "stdout has no line: $a" ;;
    --stdout-prefix)
      awk -v p="$a" 'index($0, p) == 1 { found = 1 } END { exit !found }' "$work/stdout" ||
        fail "stdout has no line starting with: $a" ;;
    --file) [ -f "$a" ] || fail "file missing: $a" ;;
    --min-lines)
      if [ ! -f "$a" ]; then fail "file missing: $a"
      else
        n=$(wc -l <"$a")
        [ "$n" -ge "$b" ] || fail "$a has $n lines, expected at least $b"
      fi ;;
    --csv-column)
      if [ ! -f "$a" ]; then fail "file missing: $a"
      else
        head -n 1 "$a" | tr -d '\r' | tr ',' '\n' | grep -qxF -- "$b" || fail "$a header has no column $b: $(head -n 1 "$a")"
      fi ;;
    --csv-complete)
      if [ ! -s "$a" ]; then fail "file missing or empty: $a"
      else
        [ "$(tail -c 1 "$a" | od -An -c | tr -d ' ')" = '\n' ] || fail "$a does not end with a newline"
        awk -F, 'NR == 1 { n = NF } NF != n { print FILENAME ":" NR ": " NF " fields, header has " n; bad = 1 }
                 { for (k = 1; k <= NF; ++k) if ($k == "") { print FILENAME ":" NR ": field " k " is empty"; bad = 1 } }
                 END { exit bad }' "$a" || fail "$a has incomplete rows"
      fi ;;
  esac
done

if [ $failed -ne 0 ]; then exit 1; fi
echo "all checks passed"
exit 0
