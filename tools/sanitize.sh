#!/usr/bin/env bash
# Builds the asan preset (clang, AddressSanitizer + UndefinedBehaviorSanitizer, no recovery: the
# first finding ends the process with a report; the libraries file by file) and runs the unit and library tests under it (the
# preset leaves out the end-to-end command tests, tests/app, which tools/test.sh runs).
# LeakSanitizer's suppressions (tests/sanitizers/lsan.supp) cover leaks inside third-party display
# libraries only, each entry named and justified there. Extra arguments go to ctest (e.g. -L io,
# -R Json).
# Usage: tools/sanitize.sh [CTEST_ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh
# The real dataset, as in tools/test.sh: when its folder exists, checked before the build and then
# required by the tests that need it (they fail instead of skipping without it).
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -d "$stpere" ]; then
  tools/check_stpere.sh "$stpere"
  MSISLAB_STPERE_DIR=$(cd "$stpere" && pwd)
  export MSISLAB_STPERE_DIR MSISLAB_REQUIRE_REAL_DATA=1
fi
tools/configure.sh asan
# The test programs and what they link, not the commands (app/, tools/): nothing here runs them.
cmake --build --preset asan --target msislab_test_programs
# halt_on_error with UBSan's no-recovery build: a finding fails the test that hit it.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
ctest --preset asan -j2 "$@"
