#!/usr/bin/env bash
# Installs what is missing, builds (Release, warnings as errors) and runs the whole test suite,
# then installs the build into a scratch prefix and builds and runs examples/ against it.
# Tests that need the real St. Pere dataset (../shared/datasets/stpere) skip when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install_deps.sh
cmake --preset ci
cmake --build --preset ci
ctest --preset ci -j2
tools/example.sh build/ci
