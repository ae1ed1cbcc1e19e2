#!/usr/bin/env bash
# The test command: install what is missing, build (warnings as errors), and run the tests through CTest.
#   scripts/test.sh          the quick tier: every unit test and a short run of every physics check
#                            (every test without the CTest label "long")
#   scripts/test.sh --full   every test, the long validations and the fuzz run included (what .ci/run calls)
# Other arguments go to ctest (e.g. -R NAME, -L LABEL, -V). docs/testing.md says what each tier checks.
set -euo pipefail
cd "$(dirname "$0")/.."
tier=quick
args=()
for a in "$@"; do
  case "$a" in
    --full) tier=full ;;
    --quick) tier=quick ;;
    -h|--help)
      sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'
      exit 0 ;;
    *) args+=("$a") ;;
  esac
done
scripts/install_deps.sh
scripts/build.sh -DSPH_WERROR=ON
cd build
if [ "$tier" = quick ]; then
  echo "test tier: quick (the long validations and the fuzz run are left out: scripts/test.sh --full runs them)"
  exec ctest --output-on-failure -j"$(nproc)" -LE '^long$' "${args[@]}"
fi
echo "test tier: full"
exec ctest --output-on-failure -j"$(nproc)" "${args[@]}"
