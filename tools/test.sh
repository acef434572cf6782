#!/usr/bin/env bash
# Installs what is missing, builds (Release, warnings as errors) and runs the whole test suite,
# then installs the build into a scratch prefix and builds and runs examples/ against it. Then the
# reliability checks (docs/reliability.md): the whole suite again under AddressSanitizer and
# UndefinedBehaviorSanitizer (tools/sanitize.sh), and every reader fuzzed for FUZZ_SECONDS (default
# 20) each (tools/fuzz.sh). MSISLAB_QUICK=1 stops after the example.
# Tests that need the real St. Pere dataset (../shared/datasets/stpere) skip when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

start=$(date +%s)
stamp() { echo "test.sh: $1 done after $(( $(date +%s) - start )) s"; }
tools/install_deps.sh
cmake --preset ci
cmake --build --preset ci
ctest --preset ci -j2
tools/example.sh build/ci
stamp "build, tests and example"
[ "${MSISLAB_QUICK:-0}" = 1 ] && exit 0
tools/sanitize.sh
stamp "sanitizer suite"
tools/fuzz.sh "${FUZZ_SECONDS:-20}"
stamp "fuzzing"
