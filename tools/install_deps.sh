#!/usr/bin/env bash
# Installs msislab's Debian 12 dependencies when any is missing (apt-get; root or sudo), by what
# the caller does: run (build and run msislab: tools/main.sh), test (and build and run the suite:
# tools/test.sh), all (and the sanitizer suite and fuzzing with clang: tools/reliability.sh; the
# default). Each set holds the one before it.
# Usage: tools/install_deps.sh [run|test|all]
set -euo pipefail

run=(
  build-essential cmake ninja-build pkg-config lld
  libeigen3-dev libembree-dev libsleef-dev libtbb-dev libopencv-dev libvtk9-dev libyaml-cpp-dev
  libcli11-dev libproj-dev
  libboost-dev libceres-dev nlohmann-json3-dev proj-data zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev  # found at configure time (the tests and benchmarks)
  xvfb xauth fonts-dejavu-core  # VTK draws the figures through an X display
)
test=(
  clang-format
  universal-ctags  # tools/check_sizes.sh: the length of every function
  python3 python3-yaml  # the tests that run tools/*.py (they fail without it)
)
all=(
  clang libclang-rt-14-dev llvm  # tools/fuzz.sh (libFuzzer) and symbolized sanitizer reports
)
case "${1:-all}" in
  run) packages=("${run[@]}") ;;
  test) packages=("${run[@]}" "${test[@]}") ;;
  all) packages=("${run[@]}" "${test[@]}" "${all[@]}") ;;
  *) echo "tools/install_deps.sh: no set '$1' (run, test, all)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
