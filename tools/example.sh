#!/usr/bin/env bash
# Installs a built msislab into a scratch prefix and builds and runs every project in examples/
# against it, as a user's own project would use the installed package (find_package(msislab)):
# simulate_and_match (one spIC match of two simulated revolutions) and run_slam (a whole
# robocentric SLAM run through slam/scan_slam_pipeline). Each exits 1 when its result is wrong.
# Usage: tools/example.sh [BUILD_DIR]   (default build/ci; after it is built)
set -euo pipefail
cd "$(dirname "$0")/.."

build="${1:-build/ci}"
[ -f "$build/CMakeCache.txt" ] || { echo "tools/example.sh: build $build first" >&2; exit 2; }
prefix="$build/install"
rm -rf "$prefix" "$build/example"
cmake --install "$build" --prefix "$prefix" >/dev/null
for example in simulate_and_match run_slam; do
  echo "== examples/$example"
  cmake -S "examples/$example" -B "$build/example/$example" -DCMAKE_PREFIX_PATH="$PWD/$prefix" \
    -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build/example/$example" -j2 >/dev/null
  "$build/example/$example/$example"
done
