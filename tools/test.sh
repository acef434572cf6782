#!/usr/bin/env bash
# The README's test command: installs what is missing, builds (Release, warnings as errors), runs
# the whole normal suite (unit, library and end-to-end command tests), then installs the build into
# a scratch prefix and builds and runs examples/ against it. The sanitizer suite and fuzzing are
# the second command, tools/reliability.sh; CI (.ci/run) runs both.
# Tests that need the real St. Pere dataset (../shared/datasets/stpere) skip when it is absent.
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
tools/install_deps.sh
stamp "packages"
cmake --preset ci
cmake --build --preset ci
stamp "build"
ctest --preset ci -j2
stamp "tests"
tools/example.sh build/ci
stamp "installed example"
