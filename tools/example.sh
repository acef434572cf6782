#!/usr/bin/env bash
# Installs a built msislab into a scratch prefix and builds and runs examples/simulate_and_match
# against it, as a user's own project would use the installed package (find_package(msislab)).
# Usage: tools/example.sh [BUILD_DIR]   (default build/ci; after it is built)
set -euo pipefail
cd "$(dirname "$0")/.."

build="${1:-build/ci}"
[ -f "$build/CMakeCache.txt" ] || { echo "tools/example.sh: build $build first" >&2; exit 2; }
prefix="$build/install"
rm -rf "$prefix" "$build/example"
cmake --install "$build" --prefix "$prefix" >/dev/null
cmake -S examples/simulate_and_match -B "$build/example" -DCMAKE_PREFIX_PATH="$PWD/$prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build/example" -j2 >/dev/null
"$build/example/simulate_and_match"
