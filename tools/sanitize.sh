#!/usr/bin/env bash
# Builds the asan preset (AddressSanitizer + UndefinedBehaviorSanitizer, no recovery: the first
# finding ends the process with a report) and runs the unit and library tests under it (the
# preset leaves out the end-to-end command tests, tests/app, which tools/test.sh runs).
# LeakSanitizer's suppressions (tests/sanitizers/lsan.supp) cover leaks inside third-party display
# libraries only, each entry named and justified there. Extra arguments go to ctest (e.g. -L io,
# -R Json).
# Usage: tools/sanitize.sh [CTEST_ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh
cmake --preset asan
# The test programs and what they link, not the commands (app/, tools/): nothing here runs them.
mapfile -t tests < <(cmake --build --preset asan --target help |
                       sed -n 's/^\.\.\. \([a-z0-9_]*_test\)$/\1/p')
cmake --build --preset asan --target "${tests[@]}"
# halt_on_error with UBSan's no-recovery build: a finding fails the test that hit it.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
ctest --preset asan -j2 "$@"
