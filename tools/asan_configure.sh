#!/usr/bin/env bash
# Configures the asan preset's build (build/asan) for tools/sanitize.sh. A build/asan configured by
# an earlier msislab with g++ (the preset was g++ then) cannot switch compilers in place: its CMake
# cache (CMakeCache.txt, CMakeFiles/), which msislab's own configure wrote, is removed first.
set -euo pipefail
cd "$(dirname "$0")/.."
cache=build/asan/CMakeCache.txt
if [ -f "$cache" ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' "$cache"; then
  echo "tools/asan_configure.sh: build/asan was configured with another compiler; reconfiguring" \
    "it with clang (the preset's)"
  rm -rf "$cache" build/asan/CMakeFiles
fi
cmake --preset asan
