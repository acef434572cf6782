#!/usr/bin/env bash
# The README's test command: installs what is missing, builds (Release, warnings as errors), runs
# the whole normal suite (unit, library and end-to-end command tests), then installs the build into
# a scratch prefix and builds and runs examples/ against it. The sanitizer suite and fuzzing are
# the second command, tools/reliability.sh; CI (.ci/run) runs both.
# The real St. Pere dataset (${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}): when its folder
# exists, it is checked before the build against the digests msislab pins for it
# (tools/check_stpere.sh, tools/datasets/stpere.sha256: a file that does not match fails the
# command, named; the Ping360 tank's pings, ../shared/datasets/ping360_tank, are checked the same
# way when that folder exists), and every test that needs it must run: one that does not find it
# fails (MSISLAB_REQUIRE_REAL_DATA=1, tests/test_support.hpp), and a skip that names it fails the
# command after ctest. Without the folder, one line names the tests that skip.
set -euo pipefail
cd "$(dirname "$0")/.."

start=$(date +%s)
stage=$start
stamp() {
  local now
  now=$(date +%s)
  echo "test.sh: $1 took $((now - stage)) s ($((now - start)) s in all)"
  stage=$now
}
tools/install_deps.sh test
stamp "packages"
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
real_data=0
if [ -d "$stpere" ]; then
  real_data=1
  tools/check_stpere.sh "$stpere"
  # Absolute: the tests run in the build tree. The tests read both (tests/test_support.hpp).
  MSISLAB_STPERE_DIR=$(cd "$stpere" && pwd)
  export MSISLAB_STPERE_DIR MSISLAB_REQUIRE_REAL_DATA=1
else
  # The tests that call MSISLAB_REQUIRE_STPERE() (DISABLED_ ones never run).
  mapfile -t real_tests < <(grep -rl --include='*.cpp' 'MSISLAB_REQUIRE_STPERE()' tests | sort |
    xargs awk '/^TEST(_F|_P)?\(/ { t = $0; sub(/^TEST[_FP]*\(/, "", t); sub(/\).*/, "", t);
                                     gsub(/ /, "", t); sub(/,/, ".", t) }
               /MSISLAB_REQUIRE_STPERE\(\)/ && t != "" { if (t !~ /\.DISABLED_/) print t; t = "" }')
  echo "test.sh: no real St. Pere dataset at $stpere (MSISLAB_STPERE_DIR), so its" \
    "${#real_tests[@]} tests skip: $(printf '%s, ' "${real_tests[@]}" | sed 's/, $//')"
fi
ping360="../shared/datasets/ping360_tank"
[ ! -d "$ping360" ] || tools/check_dataset.sh ping360_tank "$ping360"
tools/configure.sh ci
cmake --build --preset ci
stamp "build"
junit="$PWD/build/ci/Testing/test_sh_junit.xml"
ctest --preset ci -j2 --output-junit "$junit"
if [ $real_data = 1 ]; then
  # A test that skipped for want of the dataset while it is here (one that skips by other means
  # than MSISLAB_REQUIRE_STPERE, which fails instead): ctest passes it, this does not.
  skipped=$(awk 'BEGIN { RS = "</testcase>" } /<skipped/ && /St\. Pere/ {
                   sub(/.*<testcase name="/, ""); sub(/".*/, ""); print }' "$junit" | paste -sd, -)
  if [ -n "$skipped" ]; then
    echo "test.sh: the real St. Pere dataset is at $MSISLAB_STPERE_DIR, yet these tests skipped" \
      "without it: $skipped" >&2
    exit 1
  fi
fi
stamp "tests"
tools/example.sh build/ci
stamp "installed example"
