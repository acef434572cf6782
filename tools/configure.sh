#!/usr/bin/env bash
# Configures a preset's build folder (cmake --preset PRESET), for the scripts that build: a folder
# that an earlier msislab configured with another generator (the presets used Unix Makefiles
# before Ninja) or another compiler (the asan preset used g++ before clang) cannot switch in place,
# so its CMake cache (CMakeCache.txt and CMakeFiles/, which msislab's own configure wrote) is
# removed first, said in one line. Extra arguments go to cmake.
# Usage: tools/configure.sh PRESET [CMAKE_ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: tools/configure.sh PRESET [CMAKE_ARGS...]" >&2; exit 2; }
preset="$1"
shift
case "$preset" in
  release | debug | ci) dir="build/$preset" compiler="" ;;
  asan) dir="build/asan" compiler="clang++" ;;
  *) echo "tools/configure.sh: no preset '$preset' (release, debug, ci, asan)" >&2; exit 2 ;;
esac
cache="$dir/CMakeCache.txt"
if [ -f "$cache" ]; then
  why=""
  grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$cache" || why="another generator"
  if [ -n "$compiler" ] && ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=.*$compiler\$" "$cache"; then
    why="${why:+$why and }another compiler"
  fi
  if [ -n "$why" ]; then
    echo "tools/configure.sh: $dir was configured with $why; configuring it afresh as the" \
      "preset says (its CMake cache removed)"
    rm -rf "$cache" "$dir/CMakeFiles"
  fi
fi
cmake --preset "$preset" "$@"
